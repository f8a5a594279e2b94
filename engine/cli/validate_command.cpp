// `hapscene validate ENV [ENV...]`: runs each environment closed loop on the simulated
// Hapkit through the virtual-hand scenarios in simulated time, prints a table of
// verdicts (by default a line per scenario and the checks that failed; --verbose: every
// check; --quiet: one line per file), optionally writes a JSON report and an SVG
// figure. Exit 0 when every check passes or is not judged, 1 when any fails (a script
// fault always fails the "script" check), 2 for invalid input (options, or any of the
// files: the others still get their verdicts).
//
// A 2-DOF environment (its device a planar profile) runs the 2-D scenarios (sweep, press,
// swipe, release, hold, shake, free: engine/harness/planar_validate.hpp) with the same
// options; its --start is X,Y (the free scenario's start, default the profile's home).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <variant>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/per_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/validate_kind.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

// What `validate` prints and writes, from its options.
struct ValidateOutputs {
  std::optional<std::string> report_path;
  std::optional<std::string> plot_path;
  bool quiet{};
  bool verbose{};
};

// The harness options for a scene of N axes: --start read as that kind reads it
// (engine/harness/validate_kind.hpp). Fails `arguments` (exit 2) on an option the kind
// refuses (--noise where its sensors have no noise model).
template <int N>
HarnessOptions options_for(const Arguments& arguments, HarnessOptions options, const std::optional<std::string>& start_text) {
  const std::string problem = harness_options_problem<N>(options);
  if (!problem.empty()) arguments.fail("--" + problem);
  if (start_text) {
    typename ValidateKindOf<N>::Point start{};
    parse_free_start(arguments, *start_text, &start);
    ValidateKindOf<N>::set_free_start(&options, start);
  }
  return options;
}

// Validates one loaded environment, prints its verdict and writes its files; returns the
// file's exit code.
template <int N>
int validate_one(const Arguments& arguments, const EnvironmentOf<N>& environment, const HarnessOptions& options,
                 const std::optional<std::string>& start_text, const std::optional<std::string>& scenario_text,
                 const ValidateOutputs& out, bool first) {
  ValidationReportOf<N> report =
      validate_environment(environment, parse_scenarios<N>(arguments, scenario_text), options_for<N>(arguments, options, start_text));
  // The printed forms name the file in printable form (the JSON report escapes it).
  const std::string source_path = report.source_path;
  report.source_path = printable(source_path);
  if (out.quiet) {
    print_out("%s", format_report_line(report).c_str());
  } else {
    print_out("%s%s", first ? "" : "\n", (out.verbose ? format_report_table(report) : format_report_summary(report)).c_str());
  }
  report.source_path = source_path;
  if (out.report_path) write_output_file(*out.report_path, report_to_json(report).dump(2) + "\n");
  if (out.plot_path) write_output_file(*out.plot_path, validation_figure_svg(environment.scene, report));
  return report.pass ? kExitOk : kExitFailure;
}

}  // namespace

int validate_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene validate");
  // --start and --scenario mean different things for 1-DOF and 2-DOF environments: taken
  // as text, read once the files' axes are known.
  const std::optional<std::string> start_text = arguments.take_value("start");
  const HarnessOptions options = take_harness_options(arguments);
  const std::optional<std::string> scenario_text = arguments.take_value("scenario");
  ValidateOutputs out;
  out.report_path = arguments.take_value("report");
  out.plot_path = arguments.take_value("plot");
  out.quiet = arguments.take_flag("quiet");
  // The table of every check; by default a line per scenario and the failed checks.
  out.verbose = arguments.take_flag("verbose");
  if (out.quiet && out.verbose) arguments.fail("--quiet and --verbose contradict each other: give one");
  const std::vector<std::string> files = arguments.positionals();
  if (files.empty()) arguments.fail("expected at least one environment file");
  if ((out.report_path || out.plot_path) && files.size() != 1) {
    arguments.fail("--report and --plot take one environment file");
  }

  // Output files that would overwrite an input or each other, or cannot be written where
  // they are asked for, are refused before anything runs.
  {
    std::vector<std::pair<std::string, std::string>> outputs;
    if (out.report_path) outputs.emplace_back("report", *out.report_path);
    if (out.plot_path) outputs.emplace_back("plot", *out.plot_path);
    const std::string problem = output_path_problem(outputs, files);
    if (!problem.empty()) arguments.fail(problem);
  }

  // Each file is loaded once, before anything runs: the options each kind of file takes are
  // checked first. A file that cannot be loaded keeps its error for its turn.
  std::vector<std::optional<AnyEnvironment>> loaded(files.size());
  std::vector<std::exception_ptr> load_errors(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    try {
      loaded[i] = load_any_environment(files[i]);
    } catch (const std::exception&) {
      load_errors[i] = std::current_exception();
    }
  }
  const auto any_of_axes = [&](int axes) {
    return std::any_of(loaded.begin(), loaded.end(), [&](const auto& e) { return e && axes_of(*e) == axes; });
  };
#define HAPSCENE_CHECK_OPTIONS(N)                  \
  if (any_of_axes(N)) {                           \
    options_for<N>(arguments, options, start_text); \
    parse_scenarios<N>(arguments, scenario_text);  \
  }
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_CHECK_OPTIONS)
#undef HAPSCENE_CHECK_OPTIONS

  // Each file its own verdict: one that is invalid input prints its error (and, with
  // --quiet, a FAIL line) and the others still run (engine/cli/per_file.hpp).
  int exit_code = kExitOk;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const int file_code = run_for_file([&] {
      if (load_errors[i]) std::rethrow_exception(load_errors[i]);
      return std::visit(
          [&](const auto& environment) {
            return validate_one(arguments, environment, options, start_text, scenario_text, out, i == 0);
          },
          *loaded[i]);
    });
    if (file_code == kExitInvalidInput && out.quiet) print_out("FAIL %s: invalid input (see the error above)\n", printable(files[i]).c_str());
    exit_code = worst_exit_code(exit_code, file_code);
  }
  flush_out();
  return exit_code;
}

}  // namespace hapscene
