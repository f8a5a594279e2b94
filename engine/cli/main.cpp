// The `hapscene` command: dispatch to a subcommand and map errors to exit codes
// (0 success, 2 invalid input, 1 anything else). The commands, their options and all the
// help are in the table of engine/cli/command_definitions.cpp.
#include <cerrno>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/help_text.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/load/effect_schema.hpp"

namespace {

using hapscene::write_out;

bool asks_for_help(const std::vector<std::string>& args) {
  for (const std::string& arg : args) {
    if (arg == "--") return false;
    if (arg == "--help" || arg == "-h") return true;
  }
  return false;
}

// "unknown command "rn" (did you mean "run"?)"
std::string unknown_command(const std::string& command) {
  const std::string suggestion = hapscene::nearest_command(command);
  return "unknown command \"" + hapscene::printable(command) + "\"" +
         (suggestion.empty() ? std::string() : " (did you mean \"" + suggestion + "\"?)");
}

// help, version, completion, man and schema: what the command line says about itself.
std::optional<int> builtin(const std::vector<std::string>& args) {
  const std::string& command = args[0];
  if (command == "help" || command == "--help" || command == "-h") {
    // help, --help, -h: the usage; help CMD, --help CMD: the command's help.
    if (args.size() == 1) {
      write_out(hapscene::top_level_usage());
      return hapscene::kExitOk;
    }
    std::string help = hapscene::command_help(args[1]);
    // help help, help version, ...: the top-level usage describes them.
    for (const hapscene::BuiltinCommand& other : hapscene::builtin_commands()) {
      if (help.empty() && args[1] == other.name) help = hapscene::top_level_usage();
    }
    if (help.empty() || args.size() > 2) {
      throw hapscene::InputError("hapscene help: " + (args.size() > 2 ? std::string("takes one command name")
                                                                       : unknown_command(args[1])));
    }
    write_out(help);
    return hapscene::kExitOk;
  }
  if (command == "version" || command == "--version" || command == "-V") {
    if (args.size() > 1) throw hapscene::InputError("hapscene " + command + ": takes no arguments");
    write_out(std::string("hapscene ") + HAPSCENE_VERSION + "\n");
    return hapscene::kExitOk;
  }
  if (command == "completion") {
    if (args.size() != 2 || args[1] != "bash") {
      throw hapscene::InputError("hapscene completion: expected the shell: hapscene completion bash");
    }
    write_out(hapscene::bash_completion_script());
    return hapscene::kExitOk;
  }
  if (command == "man") {
    // man: roff; man --markdown: the documentation site's command reference.
    const bool markdown = args.size() == 2 && args[1] == "--markdown";
    if (args.size() > 1 && !markdown) throw hapscene::InputError("hapscene man: takes no arguments but --markdown");
    write_out(markdown ? hapscene::command_reference_markdown(HAPSCENE_VERSION) : hapscene::man_page(HAPSCENE_VERSION));
    return hapscene::kExitOk;
  }
  if (command == "schema") {
    // schema effects: the built-in effects' JSON Schema, from their declarations;
    // --markdown: the same as the documentation's reference page.
    const bool markdown = args.size() == 3 && args[2] == "--markdown";
    if (args.size() < 2 || args[1] != "effects" || (args.size() > 2 && !markdown)) {
      throw hapscene::InputError("hapscene schema: expected hapscene schema effects [--markdown]");
    }
    write_out(markdown ? hapscene::effect_reference_markdown() : hapscene::effect_schemas().dump(2) + "\n");
    return hapscene::kExitOk;
  }
  return std::nullopt;
}

int dispatch(std::vector<std::string> args) {
  if (args.empty()) {
    std::cerr << hapscene::top_level_usage();
    return hapscene::kExitInvalidInput;
  }
  const std::string command = args[0];
  try {
    if (const std::optional<int> code = builtin(args)) return *code;
    args.erase(args.begin());
    // CMD --help and CMD -h: the command's help, whatever else is given.
    const std::string help = hapscene::command_help(command);
    if (!help.empty() && asks_for_help(args)) {
      write_out(help);
      return hapscene::kExitOk;
    }
    if (command == "run") return hapscene::run_command(args);
    if (command == "probe") return hapscene::probe_command(args);
    if (command == "bench") return hapscene::bench_command(args);
    if (command == "validate") return hapscene::validate_command(args);
    if (command == "plot") return hapscene::plot_command(args);
    if (command == "test") return hapscene::test_command(args);
    if (command == "devices") return hapscene::devices_command(args);
    if (command == "calibrate") return hapscene::calibrate_command(args);
    if (command == "new") return hapscene::new_command(args);
    std::cerr << "hapscene: " << unknown_command(command) << " (try: hapscene --help)\n";
    return hapscene::kExitInvalidInput;
  } catch (const hapscene::InputError& error) {
    std::cerr << "error: " << hapscene::printable(error.what()) << "\n";
    return hapscene::kExitInvalidInput;
  } catch (const std::exception& error) {
    std::cerr << "hapscene: " << hapscene::printable(error.what()) << "\n";
    return hapscene::kExitFailure;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int code = dispatch(std::vector<std::string>(argv + 1, argv + argc));
  // Output that never arrived is a failure, not a success: "probe ... > /dev/full" exits 1
  // and says why (the first failed write's errno, kept by engine/cli/standard_output.hpp).
  if (!hapscene::report_stdout_failure()) return code == hapscene::kExitOk ? hapscene::kExitFailure : code;
  return code;
}
