#pragma once
// Command-line options: "--name value" or "--name=value", flags, and positional
// arguments. Every mistake is an InputError naming the option (exit code 2): an unknown
// option, an option given twice, a value that does not parse, and a number outside the
// range its definition accepts (engine/cli/option_definitions.hpp holds every numeric
// option of every command with its range).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/units.hpp"

namespace hapscene {

// A numeric option with a unit: its name (without "--"), its quantity and the values
// it accepts, in SI. Non-finite values are always refused.
struct QuantityOption {
  std::string_view name;
  Quantity quantity;
  double min;
  double max;
  bool min_exclusive{false};  // (min, max] instead of [min, max]
  std::string_view unit{};    // shown after numbers in messages; default the SI unit
};

// A whole-number option: digits only (no sign, no fraction, no unit), in [min, max].
struct WholeOption {
  std::string_view name;
  std::uint64_t min;
  std::uint64_t max;
  std::string_view what{"a whole number"};  // "a seed", "bits per second": for messages
};

class Arguments {
 public:
  // `command` names the subcommand in messages ("hapscene probe").
  Arguments(std::vector<std::string> args, std::string command);

  // Removes and returns the value of --name, if given; given twice is an error.
  std::optional<std::string> take_value(std::string_view name);
  // The same, read and range-checked by the option's definition.
  std::optional<double> take(const QuantityOption& option);
  std::optional<std::uint64_t> take(const WholeOption& option);
  // Removes --name and says whether it was given; given twice is an error.
  bool take_flag(std::string_view name);
  // What is left: positional arguments. Refuses options nobody took.
  std::vector<std::string> positionals() const;

  [[noreturn]] void fail(const std::string& message) const;
  const std::string& command() const { return command_; }

 private:
  std::vector<std::string> args_;
  std::string command_;
};

// Reads `text` as a value of `option` (quantity and range); `what` names it in messages
// ("hapscene probe: --x STEP").
double parse_option_quantity(const std::string& text, const QuantityOption& option, const std::string& what);

// Reads `text` as a whole number in [option.min, option.max] with read_whole_number
// (engine/base/whole_number.hpp: "10x", "-1", "+3", "1e3" and "" are refused), and values
// past 2^64 - 1 say so. The one parser of integers on the command line.
std::uint64_t parse_whole_number(const std::string& text, const WholeOption& option, const std::string& what);

// The accepted range as messages show it: "[0, 100] counts", "(0 s, 86400 s]".
std::string describe_range(const QuantityOption& option);

}  // namespace hapscene
