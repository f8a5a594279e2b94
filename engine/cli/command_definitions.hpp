#pragma once
// The command line's one description: every command, its forms, and every option with its
// short form, value name, default, unit and range, and help. The parser (Arguments), the
// top-level usage, `hapscene CMD --help` and `hapscene help CMD`, the bash completion
// script and the man page are all generated from it (engine/cli/command_definitions.cpp
// holds the table; engine/cli/help_text.cpp the generators), so they cannot drift apart.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/cli/arguments.hpp"

namespace hapscene {

// What the shell offers for a value or a positional argument.
enum class Completion {
  none,         // a number or free text: nothing offered
  environment,  // *.json and *.lua files, and folders
  json,         // *.json files, and folders
  spec,         // *.test.json files, and folders
  output,       // any file name, and folders
  folder,       // folders only
  values,       // OptionDefinition::values (a comma-separated list when `list`)
  device,       // --device forms: sim, hil, hil:FILE.elf, serial:PORT, haply:PORT
};

struct OptionDefinition {
  std::string_view name;               // without "--"
  char short_name{0};                  // 'q' for -q; 0: none
  std::string_view value_name{};       // "T", "FILE.csv"; empty: a flag
  std::string_view help{};             // what it does, a sentence without a final period
  std::string_view default_text{};     // "2 s"; empty: no default shown
  const QuantityOption* quantity{};    // the unit and range checked (Arguments::take) and shown
  const WholeOption* whole{};          // the same for whole numbers
  std::string_view values{};           // enumerated values, space-separated
  Completion completion{Completion::none};
  bool list{false};                    // values: a comma-separated list of them
};

// One form of a command. A command has one form, or several selected by a flag (bench:
// the default tables and --accuracy, --stress, --soak, --callgrind).
struct CommandDefinition {
  std::string_view name;            // "run"
  std::string_view mode{};          // the flag that selects this form ("soak"); empty: the default form
  std::string_view synopsis{};      // after "hapscene NAME [--MODE]": "ENV [ENV...] [options]"
  std::string_view summary{};       // one line, for the top-level usage
  std::string_view description{};   // a paragraph for CMD --help and the man page
  std::span<const OptionDefinition> options{};
  Completion positionals{Completion::none};
  std::span<const std::string_view> examples{};  // whole command lines, without "hapscene "
};

// Every form of every command, in the order the usage lists them.
std::span<const CommandDefinition> command_definitions();

// Commands that are not parsed through the table (help, version, completion, man).
struct BuiltinCommand {
  std::string_view name;
  std::string_view synopsis;
  std::string_view summary;
};
std::span<const BuiltinCommand> builtin_commands();

// Every command name, once each, in order (the table's and the built-in ones).
std::vector<std::string_view> command_names();

// The form of `command` that `args` select (by its mode flag, at most one of them).
// Throws InputError ("hapscene bench: --soak and --stress are different forms; give one")
// when they select several. Null when there is no such command.
const CommandDefinition* find_command_form(std::string_view command, const std::vector<std::string>& args);

// The closest command name to `word` for "did you mean", or empty.
std::string nearest_command(std::string_view word);

}  // namespace hapscene
