#pragma once
// Command-line options: "--name value", "--name=value", "-n value", "-nvalue", flags,
// positional arguments, and "--" before positionals that start with "-". The options a
// command accepts are its entry in the table of engine/cli/command_definitions.cpp; the
// command line is read against it once, left to right, when Arguments is made. Every
// mistake is an InputError naming the option (exit code 2): an unknown option (with the
// nearest known one), an option given twice, a missing value, a value that does not
// parse, and a number outside the range its definition accepts
// (engine/cli/option_definitions.hpp holds every numeric option with its range).
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

struct CommandDefinition;
struct OptionDefinition;

class Arguments {
 public:
  // `command` names the subcommand in messages ("hapscene probe"); its options come from
  // the table (the form of the command the arguments select, e.g. bench --soak). Throws
  // InputError for a command line the table refuses.
  Arguments(std::vector<std::string> args, std::string command);

  // Removes and returns the value of --name, if given; given twice is an error.
  std::optional<std::string> take_value(std::string_view name);
  // The same, read and range-checked by the option's definition.
  std::optional<double> take(const QuantityOption& option);
  std::optional<std::uint64_t> take(const WholeOption& option);
  // Removes --name and says whether it was given; given twice is an error.
  bool take_flag(std::string_view name);
  // The positional arguments, in order. An option given that the command never took is
  // a table entry the code does not read: std::logic_error (exit 1), never ignored.
  std::vector<std::string> positionals() const;

  [[noreturn]] void fail(const std::string& message) const;
  const std::string& command() const { return command_; }
  const CommandDefinition& form() const { return *form_; }

 private:
  struct Given {
    const OptionDefinition* option;
    std::string value;  // empty for a flag
    bool taken{false};
  };
  // The given option `name`, if any; std::logic_error when the form does not define it
  // (`flag`: as a flag, else as an option with a value).
  Given* find_given(std::string_view name, bool flag);
  void parse(const std::vector<std::string>& args);
  // "unknown option --sed (did you mean --seed?)"
  std::string unknown_option_message(const std::string& written) const;

  std::string command_;
  const CommandDefinition* form_{};
  std::vector<Given> given_;
  std::vector<std::string> positionals_;
  bool mode_given_{false};  // the form's mode flag (bench --soak)
  bool mode_taken_{false};
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
