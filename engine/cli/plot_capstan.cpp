// `hapscene plot` of a one-axis (capstan) environment: the force-displacement curve and
// one validate scenario's time series (--scenario, default sweep), with --noise and
// --start as validate takes them (engine/harness/figures.hpp).
#include <cmath>

#include "engine/cli/harness_options.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/plot_kind.hpp"
#include "engine/harness/figures.hpp"
#include "engine/harness/force_field.hpp"
#include "engine/harness/validate.hpp"

namespace hapscene {

PlotFigure plot_figure(const Arguments& arguments, const std::string& /*file*/, const EnvironmentOf<1>& environment,
                       const PlotTexts& texts, HarnessOptions options) {
  if (texts.grid) arguments.fail("--grid: only for a 2-DOF environment (its device a planar profile)");
  if (texts.width) arguments.fail("--width: only for a 2-DOF environment (its device a planar profile)");
  if (texts.noise) options.noise_counts = parse_option_quantity(*texts.noise, option::noise, "hapscene plot: --noise");
  if (texts.start) {
    options.free_start_m = parse_option_quantity(*texts.start, option::free_start, "hapscene plot: --start");
  }
  const std::vector<ScenarioKind> kinds = parse_scenarios<1>(arguments, texts.scenario);
  if (kinds.size() > 1) arguments.fail("--scenario: plot draws one scenario");

  const Scene& scene = environment.scene;
  options.thresholds = environment.validate;
  const ForceField field = probe_force_field(scene, options.thresholds.stiff_threshold_N_per_m);
  const ScenarioKind kind = kinds.empty() ? ScenarioKind::sweep : kinds[0];
  const ScenarioResult result = run_scenario(scene, field, build_scenario(kind, scene, field, options), options);
  // Script faults: the field scan's, the curve's and the run's, each once.
  PlotFigure figure;
  figure.faults = field.faults;
  figure.svg = scene_figure_svg(scene, result, &figure.faults);
  for (const auto& fault : result.metrics.script_faults) {
    figure.faults.add(fault.message, fault.where + " of the " + result.scenario.name + " run", INFINITY);
  }
  // Too slow for the loop: the field scan's verdict, else the run's (one message).
  figure.too_slow = field.too_slow;
  for (const CheckResult& check : result.checks) {
    if (figure.too_slow.empty() && check.name == "pace" && !check.pass) figure.too_slow = check.detail;
  }
  return figure;
}

}  // namespace hapscene
