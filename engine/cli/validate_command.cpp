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
#include <fstream>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/per_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/figures.hpp"
#include "engine/harness/planar_report.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/harness/report.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

int validate_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene validate");
  // --start and --scenario mean different things for 1-DOF and 2-DOF environments: taken
  // as text, read once the files' axes are known.
  const std::optional<std::string> start_text = arguments.take_value("start");
  HarnessOptions options = take_harness_options(arguments);
  const std::optional<std::string> scenario_text = arguments.take_value("scenario");
  const std::optional<std::string> report_path = arguments.take_value("report");
  const std::optional<std::string> plot_path = arguments.take_value("plot");
  const bool quiet = arguments.take_flag("quiet");
  // The table of every check; by default a line per scenario and the failed checks.
  const bool verbose = arguments.take_flag("verbose");
  if (quiet && verbose) arguments.fail("--quiet and --verbose contradict each other: give one");
  const std::vector<std::string> files = arguments.positionals();
  if (files.empty()) arguments.fail("expected at least one environment file");
  if ((report_path || plot_path) && files.size() != 1) {
    arguments.fail("--report and --plot take one environment file");
  }

  // The axes of each file (one that cannot be read is left to its load, which reports it);
  // the options each kind of file takes are checked before anything runs.
  std::vector<int> axes(files.size(), 1);
  for (std::size_t i = 0; i < files.size(); ++i) {
    try {
      axes[i] = environment_axes(files[i]);
    } catch (const InputError&) {
      axes[i] = 1;
    }
  }
  const bool any_planar = std::find(axes.begin(), axes.end(), 2) != axes.end();
  const bool any_capstan = std::find(axes.begin(), axes.end(), 1) != axes.end();
  std::vector<ScenarioKind> kinds;
  std::vector<PlanarValidateKind> planar_kinds;
  if (any_capstan) {
    if (start_text) options.free_start_m = parse_option_quantity(*start_text, option::free_start, "hapscene validate: --start");
    kinds = parse_scenarios(arguments, scenario_text);
  }
  if (any_planar) {
    // The planar simulator's sensors have no noise model yet: refused rather than ignored.
    if (options.noise_counts >= 0.0) arguments.fail("--noise: not yet for a 2-DOF environment");
    if (start_text) options.free_start_planar_m = parse_planar_point(arguments, "start", *start_text, option::run_start);
    planar_kinds = parse_planar_scenarios(arguments, scenario_text);
  }

  // Output files that would overwrite an input or each other, or cannot be written where
  // they are asked for, are refused before anything runs.
  {
    std::vector<std::pair<std::string, std::string>> outputs;
    if (report_path) outputs.emplace_back("report", *report_path);
    if (plot_path) outputs.emplace_back("plot", *plot_path);
    const std::string problem = output_path_problem(outputs, files);
    if (!problem.empty()) arguments.fail(problem);
  }

  // Each file its own verdict: one that is invalid input prints its error (and, with
  // --quiet, a FAIL line) and the others still run (engine/cli/per_file.hpp).
  int exit_code = kExitOk;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const int file_code = run_for_file([&] {
      if (axes[i] == 2) {
        const PlanarEnvironment environment = load_planar_environment(files[i]);
        const PlanarScene& scene = environment.scene;
        HarnessOptions file_options = options;
        file_options.thresholds = environment.validate;
        PlanarValidationReport report;
        try {
          report = validate_planar_scene(scene, planar_kinds, file_options);
        } catch (const InputError& error) {
          throw InputError(files[i] + ": a scenario cannot start where it asks (" + error.what() + ")");
        }
        // The printed forms name the file in printable form (the JSON report escapes it);
        // the records are not needed for that.
        PlanarValidationReport shown;
        shown.scene_name = report.scene_name;
        shown.source_path = printable(report.source_path);
        shown.rate_hz = report.rate_hz;
        shown.bound = report.bound;
        shown.scripts = report.scripts;
        shown.options = report.options;
        shown.scene_checks = report.scene_checks;
        for (const PlanarScenarioResult& s : report.scenarios) {
          shown.scenarios.push_back({s.scenario, s.metrics, s.checks, {}, {}, s.pass});
        }
        if (quiet) {
          print_out("%s", format_planar_report_line(shown).c_str());
        } else {
          print_out("%s%s", i > 0 ? "\n" : "",
                    (verbose ? format_planar_report_table(shown) : format_planar_report_summary(shown)).c_str());
        }
        if (report_path) write_output_file(*report_path, planar_report_to_json(report).dump(2) + "\n");
        if (plot_path) write_output_file(*plot_path, planar_validation_figure_svg(scene, report));
        return report.pass ? kExitOk : kExitFailure;
      }
      const Environment environment = load_environment(files[i]);
      const Scene& scene = environment.scene;
      HarnessOptions file_options = options;
      file_options.thresholds = environment.validate;
      const ValidationReport report = validate_scene(scene, kinds, file_options);
      // The printed forms name the file in printable form (the JSON report escapes it).
      ValidationReport shown = report;
      shown.source_path = printable(report.source_path);
      if (quiet) {
        print_out("%s", format_report_line(shown).c_str());
      } else {
        print_out("%s%s", i > 0 ? "\n" : "", (verbose ? format_report_table(shown) : format_report_summary(shown)).c_str());
      }
      if (report_path) write_output_file(*report_path, report_to_json(report).dump(2) + "\n");
      if (plot_path) write_output_file(*plot_path, validation_figure_svg(scene, report));
      return report.pass ? kExitOk : kExitFailure;
    });
    if (file_code == kExitInvalidInput && quiet) print_out("FAIL %s: invalid input (see the error above)\n", printable(files[i]).c_str());
    exit_code = worst_exit_code(exit_code, file_code);
  }
  flush_out();
  return exit_code;
}

}  // namespace hapscene
