// `hapscene plot ENV [--scenario NAME] [--output FILE.svg]`: a figure of the environment
// as an SVG file, drawn by its device kind (plot_kind.hpp): for one axis the
// force-displacement curve and one scenario's time series (default: sweep); for two the
// force field over the workspace, a run's paths and its time series per axis. The file is
// loaded once. Script faults met on the way (open loop or in the run) go to stderr, each
// once, after the figure is written; then the exit code is 1. So does a failed "pace"
// check (scripts too slow for the loop, seen before the field scan or during the run): its
// message once, exit 1; and a non-finite force the run's safety stage zeroed.
#include <cstdio>
#include <filesystem>
#include <string>
#include <variant>

#include "engine/base/errors.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/plot_kind.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

// The figure's default path: the environment file's name with .svg, in the working folder
// (wall.json: wall.svg), as users expect; never the "name" inside the file, which may hold
// spaces or a '/'.
std::string default_figure_path(const std::string& environment_file) {
  return std::filesystem::path(environment_file).stem().string() + ".svg";
}

}  // namespace

int plot_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene plot");
  PlotTexts texts;
  texts.scenario = arguments.take_value("scenario");
  texts.noise = arguments.take_value("noise");
  texts.start = arguments.take_value("start");
  texts.grid = arguments.take(option::plot_grid);
  texts.width = arguments.take(option::plot_width);
  const HarnessOptions options = take_harness_options(arguments);
  const std::optional<std::string> out_path = arguments.take_value("output");
  const std::vector<std::string> files = arguments.positionals();
  if (files.size() != 1) arguments.fail("expected one environment file");
  if (out_path) {
    const std::string problem = output_path_problem({{"output", *out_path}}, files);
    if (!problem.empty()) arguments.fail(problem);
  }
  const AnyEnvironment environment = load_any_environment(files[0]);
  const PlotFigure figure =
      std::visit([&](const auto& e) { return plot_figure(arguments, files[0], e, texts, options); }, environment);

  const std::string path = out_path.value_or(default_figure_path(files[0]));
  write_output_file(path, figure.svg);
  print_out("wrote %s\n", printable(path).c_str());
  flush_out();
  if (!figure.note.empty()) std::fprintf(stderr, "note: %s\n", figure.note.c_str());
  if (!figure.too_slow.empty()) std::fprintf(stderr, "pace: %s\n", figure.too_slow.c_str());
  for (const std::string& line : figure.faults.report_lines("in the workspace")) std::fprintf(stderr, "%s\n", line.c_str());
  const bool fault_seen = !figure.faults.empty() || !figure.too_slow.empty() || figure.nonfinite_seen;
  return fault_seen ? kExitFailure : kExitOk;
}

}  // namespace hapscene
