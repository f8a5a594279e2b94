// `hapscene validate ENV [ENV...]`: runs each environment closed loop on the simulated
// Hapkit through the virtual-hand scenarios in simulated time, prints a table of
// verdicts (--quiet: one line per file), optionally writes a JSON report and an SVG
// figure. Exit 0 when every check passes or is not judged, 1 when any fails (a script
// fault always fails the "script" check), 2 for invalid input (options, or any of the
// files: the others still get their verdicts).
#include <cstdio>
#include <fstream>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/per_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/figures.hpp"
#include "engine/harness/report.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

int validate_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene validate");
  const HarnessOptions options = take_harness_options(arguments);
  const std::vector<ScenarioKind> kinds = take_scenarios(arguments);
  const std::optional<std::string> report_path = arguments.take_value("report");
  const std::optional<std::string> plot_path = arguments.take_value("plot");
  const bool quiet = arguments.take_flag("quiet");
  const std::vector<std::string> files = arguments.positionals();
  if (files.empty()) arguments.fail("expected at least one environment file");
  if ((report_path || plot_path) && files.size() != 1) {
    arguments.fail("--report and --plot take one environment file");
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
        print_out("%s%s", i > 0 ? "\n" : "", format_report_table(shown).c_str());
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
