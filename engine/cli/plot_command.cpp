// `hapscene plot ENV [--scenario NAME] [--output FILE.svg]`: the force-displacement curve and
// one scenario's time series (default: sweep) as an SVG figure. Script faults met on the
// way (open loop or in the run) go to stderr, each once, after the figure is written;
// then the exit code is 1. So does a failed "pace" check (scripts too slow for the loop,
// seen before the field scan or during the run): its message once, exit 1.
//
// For a 2-DOF environment (its device a planar profile): the open-loop force field over
// the workspace with the shapes, one closed-loop scenario's handle and proxy paths, and
// its time series per axis (engine/harness/planar_figure.hpp); --scenario sweep (default),
// press, line or circle; --grid N arrows along the workspace's longer side (default 24);
// --width PX the figure's width (default 900). --noise and --start are 1-DOF options.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/units.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/figures.hpp"
#include "engine/harness/planar_figure.hpp"
#include "engine/harness/planar_scenario.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

// The figure's default path: the environment file's name with .svg, in the working folder
// (wall.json: wall.svg), as users expect; never the "name" inside the file, which may hold
// spaces or a '/'.
std::string default_figure_path(const std::string& environment_file) {
  return std::filesystem::path(environment_file).stem().string() + ".svg";
}

// Options read as text before the scene's axes are known.
struct PlotTexts {
  std::optional<std::string> scenario;
  std::optional<std::string> noise;
  std::optional<std::string> start;
  std::optional<std::uint64_t> grid;
  std::optional<std::uint64_t> width;
};

// --scenario for a planar scene: one of the planar scenarios.
PlanarScenarioKind planar_scenario_option(const Arguments& arguments, const std::optional<std::string>& text) {
  if (!text) return PlanarScenarioKind::sweep;
  if (text->find(',') != std::string::npos) arguments.fail("--scenario: plot draws one scenario");
  if (const std::optional<PlanarScenarioKind> kind = planar_scenario_kind_named(*text)) return *kind;
  if (scenario_kind_named(*text)) {
    arguments.fail("--scenario: \"" + *text +
                   "\" is a 1-DOF scenario; a 2-DOF environment takes sweep, press, line or circle");
  }
  const std::string suggestion = nearest_name(*text, kPlanarScenarioNames);
  arguments.fail("--scenario: unknown scenario \"" + *text + "\" (one of sweep, press, line, circle" +
                 (suggestion.empty() ? ")" : "; did you mean \"" + suggestion + "\"?)"));
}

int plot_planar(const Arguments& arguments, const std::string& file, const PlotTexts& texts,
                const HarnessOptions& options, const std::optional<std::string>& out_path) {
  if (texts.noise) arguments.fail("--noise: only for a 1-DOF environment (the 2-DOF device reads its profile's sensors)");
  if (texts.start) arguments.fail("--start: only for a 1-DOF environment (a 2-DOF plot starts at the profile's home)");
  const PlanarScenarioKind kind = planar_scenario_option(arguments, texts.scenario);
  PlanarFigureOptions figure;
  if (texts.grid) figure.grid = static_cast<int>(*texts.grid);
  if (texts.width) figure.width_px = static_cast<int>(*texts.width);

  const PlanarScene scene = load_planar_environment_file(file);
  const PlanarScenario scenario = build_planar_scenario(kind, scene, options);
  PlanarScenarioRun run;
  if (scenario.applicable) {
    try {
      run = run_planar_scenario(scene, scenario, options.seed);
    } catch (const InputError& error) {
      throw InputError(file + ": the " + scenario.name + " scenario cannot start at the profile's home: " +
                       error.what());
    }
  }
  std::string what = scenario.name + " (" + scenario.description + ")";
  if (run.ticks_per_bucket > 1) {
    what += ", first tick and highest force of every " + std::to_string(run.ticks_per_bucket) + " ticks";
  }
  const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(scene);
  const std::string proxy_label =
      scenario.proxy_index >= 0
          ? std::string("proxy of the ") + planar_shape_kind_name(shapes[static_cast<std::size_t>(scenario.proxy_index)].kind)
          : std::string();
  // Script faults: the field scan's and the run's, each once (as in 1-D).
  ScriptFaultLog faults;
  const std::string svg = planar_figure_svg(scene, figure, run.records, what, proxy_label, &faults);
  for (const ScriptReport& script : run.summary.scripts) {
    if (!script.disabled) continue;
    faults.add(script.fault, printf_string("t %.3f s of the %s run", script.fault_time_s, scenario.name.c_str()),
               std::numeric_limits<double>::infinity());
  }
  const std::string path = out_path.value_or(default_figure_path(file));
  write_output_file(path, svg);
  print_out("wrote %s\n", printable(path).c_str());
  flush_out();
  if (!scenario.applicable) {
    std::fprintf(stderr, "note: %s: %s; the figure shows the force field only\n", scenario.name.c_str(),
                 scenario.description.c_str());
  }
  for (const std::string& line : faults.report_lines("in the workspace")) std::fprintf(stderr, "%s\n", line.c_str());
  // A script fault, or a non-finite force the run's safety stage zeroed, is a fault seen.
  return faults.empty() && run.summary.safety.nonfinite_faults == 0 ? kExitOk : kExitFailure;
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
  HarnessOptions options = take_harness_options(arguments);
  const std::optional<std::string> out_path = arguments.take_value("output");
  const std::vector<std::string> files = arguments.positionals();
  if (files.size() != 1) arguments.fail("expected one environment file");
  if (out_path) {
    const std::string problem = output_path_problem({{"output", *out_path}}, files);
    if (!problem.empty()) arguments.fail(problem);
  }
  if (environment_axes(files[0]) == 2) return plot_planar(arguments, files[0], texts, options, out_path);
  if (texts.grid) arguments.fail("--grid: only for a 2-DOF environment (its device a planar profile)");
  if (texts.width) arguments.fail("--width: only for a 2-DOF environment (its device a planar profile)");
  if (texts.noise) options.noise_counts = parse_option_quantity(*texts.noise, option::noise, "hapscene plot: --noise");
  if (texts.start) {
    options.free_start_m = parse_option_quantity(*texts.start, option::free_start, "hapscene plot: --start");
  }
  const std::vector<ScenarioKind> kinds = parse_scenarios<1>(arguments, texts.scenario);
  if (kinds.size() > 1) arguments.fail("--scenario: plot draws one scenario");

  const Environment environment = load_environment(files[0]);
  const Scene& scene = environment.scene;
  options.thresholds = environment.validate;
  const ForceField field = probe_force_field(scene, options.thresholds.stiff_threshold_N_per_m);
  const ScenarioKind kind = kinds.empty() ? ScenarioKind::sweep : kinds[0];
  const ScenarioResult result = run_scenario(scene, field, build_scenario(kind, scene, field, options), options);
  // Script faults: the field scan's, the curve's and the run's, each once.
  ScriptFaultLog faults = field.faults;
  const std::string svg = scene_figure_svg(scene, result, &faults);
  for (const auto& fault : result.metrics.script_faults) {
    faults.add(fault.message, fault.where + " of the " + result.scenario.name + " run", INFINITY);
  }
  const std::string path = out_path.value_or(default_figure_path(files[0]));
  write_output_file(path, svg);
  print_out("wrote %s\n", printable(path).c_str());
  flush_out();
  // Too slow for the loop: the field scan's verdict, else the run's (one message).
  std::string too_slow = field.too_slow;
  for (const CheckResult& check : result.checks) {
    if (too_slow.empty() && check.name == "pace" && !check.pass) too_slow = check.detail;
  }
  if (!too_slow.empty()) std::fprintf(stderr, "pace: %s\n", too_slow.c_str());
  for (const std::string& line : faults.report_lines("in the workspace")) std::fprintf(stderr, "%s\n", line.c_str());
  return faults.empty() && too_slow.empty() ? kExitOk : kExitFailure;
}

}  // namespace hapscene
