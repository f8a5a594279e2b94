#pragma once
// Command-line options: "--name value" or "--name=value", flags, and positional
// arguments. Every mistake is an InputError naming the option (exit code 2).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/load/units.hpp"

namespace hapscene {

class Arguments {
 public:
  // `command` names the subcommand in messages ("hapscene probe").
  Arguments(std::vector<std::string> args, std::string command);

  // Removes and returns the value of --name, if given.
  std::optional<std::string> take_value(std::string_view name);
  // The same, read as a quantity (a number in SI or a string with a unit).
  std::optional<double> take_quantity(std::string_view name, Quantity quantity);
  // Removes --name and says whether it was given.
  bool take_flag(std::string_view name);
  // What is left: positional arguments. Refuses options nobody took.
  std::vector<std::string> positionals() const;

  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::vector<std::string> args_;
  std::string command_;
};

// Reads a quantity for an option; `what` names it in the message.
double parse_option_quantity(const std::string& text, Quantity quantity, const std::string& what);

}  // namespace hapscene
