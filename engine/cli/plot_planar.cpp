// `hapscene plot` of a two-axis (planar) environment: the open-loop force field over the
// workspace with the shapes, one closed-loop scenario's handle and proxy paths, and its
// time series per axis (engine/harness/planar_figure.hpp); --scenario sweep (default),
// press, line or circle; --grid N arrows along the workspace's longer side (default 24);
// --width PX the figure's width (default 900). --noise and --start are 1-DOF options.
#include <limits>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/plot_kind.hpp"
#include "engine/harness/planar_figure.hpp"
#include "engine/harness/planar_scenario.hpp"
#include "engine/harness/planar_shape_list.hpp"

namespace hapscene {
namespace {

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

}  // namespace

PlotFigure plot_figure(const Arguments& arguments, const std::string& file, const EnvironmentOf<2>& environment,
                       const PlotTexts& texts, HarnessOptions options) {
  if (texts.noise) arguments.fail("--noise: only for a 1-DOF environment (the 2-DOF device reads its profile's sensors)");
  if (texts.start) arguments.fail("--start: only for a 1-DOF environment (a 2-DOF plot starts at the profile's home)");
  const PlanarScenarioKind kind = planar_scenario_option(arguments, texts.scenario);
  PlanarFigureOptions figure_options;
  if (texts.grid) figure_options.grid = static_cast<int>(*texts.grid);
  if (texts.width) figure_options.width_px = static_cast<int>(*texts.width);

  const PlanarScene& scene = environment.scene;
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
  PlotFigure figure;
  figure.svg = planar_figure_svg(scene, figure_options, run.records, what, proxy_label, &figure.faults);
  for (const ScriptReport& script : run.summary.scripts) {
    if (!script.disabled) continue;
    figure.faults.add(script.fault, printf_string("t %.3f s of the %s run", script.fault_time_s, scenario.name.c_str()),
                      std::numeric_limits<double>::infinity());
  }
  if (!scenario.applicable) figure.note = scenario.name + ": " + scenario.description + "; the figure shows the force field only";
  figure.nonfinite_seen = run.summary.safety.nonfinite_faults > 0;
  return figure;
}

}  // namespace hapscene
