#include "engine/harness/planar_validate.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "engine/base/format.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

PlanarScenarioResult run_planar_validate_scenario(const PlanarScene& scene, const PlanarValidateScenario& scenario,
                                                  const HarnessOptions& options) {
  PlanarScenarioResult result;
  result.scenario = scenario;
  if (!scenario.applicable) return result;

  PlanarSimulationConfig simulation;
  simulation.hand = scenario.hand;
  simulation.noise_seed = options.seed;
  simulation.start_q_rad = planar_joint_angles_at(scene.device, scenario.start_m);
  PlanarProfile profile = scene.device;
  if (options.noise_counts >= 0.0) profile.plant.sensor_noise_counts = options.noise_counts;
  const auto device = std::make_unique<SimulatedPlanar>(profile, simulation);

  const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(scene);
  const auto ticks = static_cast<std::size_t>(std::llround(scenario.duration_s * scene.rate_hz));
  std::atomic<bool> stop{false};
  PlanarValidateRecorder recorder(device.get(), ticks + 1, shapes.size(), scene.period_s, &stop);
  RunOptions run_options;
  run_options.duration_s = scenario.duration_s;
  run_options.pacing = Pacing::simulated_time;
  run_options.stop_requested = &stop;
  const RunSummaryOf<2> summary = run_scene(scene, *device, run_options, &recorder);

  result.metrics = measure_planar_run(scene, shapes, recorder.records, recorder.proxies_m, device->plant().q_rad(),
                                      device->x_m(), summary, scenario.watch_from_s);
  if (recorder.pace.too_slow()) {
    result.checks = {CheckResult{"pace", 1.0, 0.0, "", false,
                                 printf_string("too slow for the %g Hz loop: the run's ticks took more CPU time than "
                                               "the tick period; stopped after %.3f s",
                                               scene.rate_hz, result.metrics.duration_s)}};
  } else {
    result.checks = judge_planar_scenario(scene, options.thresholds, shapes, result.metrics);
  }
  result.records = std::move(recorder.records);
  result.proxies_m = std::move(recorder.proxies_m);
  result.pass = std::all_of(result.checks.begin(), result.checks.end(), [](const CheckResult& c) { return c.pass; });
  return result;
}

PlanarValidationReport validate_planar_scene(const PlanarScene& scene, const std::vector<PlanarValidateKind>& kinds,
                                             const HarnessOptions& options) {
  PlanarValidationReport report;
  report.scene_name = scene.name;
  report.source_path = scene.source_path;
  report.rate_hz = scene.rate_hz;
  report.options = options;
  report.bound = planar_stiffness_bound(scene);
  report.shapes = planar_shape_list(scene).size();
  report.load_warnings = scene.load_warnings;
  if (!scene.load_warnings.empty()) {
    std::string detail;
    for (const std::string& warning : scene.load_warnings) detail += (detail.empty() ? "" : "; ") + warning;
    report.scene_checks.push_back(CheckResult{"effects", static_cast<double>(scene.load_warnings.size()), 0.0,
                                              "effects", false, detail});
    report.pass = false;
  }
  std::vector<PlanarValidateKind> chosen = kinds;
  if (chosen.empty()) {
    for (std::size_t i = 0; i < std::size(kPlanarValidateNames); ++i) chosen.push_back(static_cast<PlanarValidateKind>(i));
  }
  for (const PlanarValidateKind kind : chosen) {
    const PlanarValidateScenario scenario = build_planar_validate_scenario(kind, scene, options);
    report.scenarios.push_back(run_planar_validate_scenario(scene, scenario, options));
    report.pass = report.pass && report.scenarios.back().pass;
  }
  return report;
}

}  // namespace hapscene
