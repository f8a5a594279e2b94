#include "engine/harness/planar_validate.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/planar_open_loop.hpp"
#include "engine/harness/planar_script_potential.hpp"
#include "engine/harness/stop_request.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

PlanarScenarioResult run_planar_validate_scenario(const PlanarScene& scene, const PlanarValidateScenario& scenario,
                                                  const HarnessOptions& options,
                                                  const PlanarScriptPotential* script_potential) {
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

  const std::vector<PlanarShapeGeometry> shapes = planar_scenario_shapes(scene);
  const auto ticks = static_cast<std::size_t>(std::llround(scenario.duration_s * scene.rate_hz));
  std::atomic<bool> stop{false};
  PlanarValidateRecorder recorder(device.get(), ticks + 1, shapes.size(), scene.period_s, &stop);
  RunOptions run_options;
  run_options.duration_s = scenario.duration_s;
  run_options.pacing = Pacing::simulated_time;
  run_options.stop_requested = &stop;
  const RunSummaryOf<2> summary = run_scene(scene, *device, run_options, &recorder);
  throw_if_stop_requested();  // the run stopped early on request: nothing to judge

  result.metrics = measure_planar_run(scene, shapes, recorder.records, recorder.proxies_m, device->plant().q_rad(),
                                      device->x_m(), summary, scenario.watch_from_s, script_potential);
  if (recorder.pace.too_slow()) {
    result.checks = {CheckResult{"pace", 1.0, 0.0, "", false,
                                 printf_string("too slow for the %g Hz loop: the run's ticks took more CPU time than "
                                               "the tick period; stopped after %.3f s",
                                               scene.rate_hz, result.metrics.duration_s)}};
  } else {
    result.checks = judge_planar_scenario(scene, options.thresholds, shapes, result.metrics);
    // The passivity check says where the scripts' stored energy came from.
    if (script_potential != nullptr) {
      for (CheckResult& check : result.checks) {
        if (check.name == "passivity") check.detail += describe_script_potential(scene, *script_potential);
      }
    }
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
  report.shapes = planar_scenario_shapes(scene).size();
  report.scripts = scene.script_count;
  report.load_warnings = scene.load_warnings;
  // Scripts too slow for the loop: nothing else is run (as in 1-D). The first calls are
  // timed alone, then the open-loop scans' (ScanPace).
  const auto too_slow = [&](CheckResult pace) {
    report.scene_checks = {std::move(pace)};
    report.pass = false;
    return report;
  };
  if (const std::optional<CheckResult> pace = check_script_pace(scene)) return too_slow(*pace);
  // The scene as a whole: effects that never act, and the faults an open-loop scan of the
  // workspace meets where no scenario may go (every kPlanarFaultScanStep_m at rest, t = 0,
  // each fault with the first point that met it, as fresh instances give it).
  if (auto effects = scene_effects_check(scene.load_warnings)) report.scene_checks.push_back(*effects);
  // The energy the scripts store, once for every scenario (planar_script_potential.hpp).
  PlanarScriptPotential script_potential;
  try {
    if (scene.script_count > 0) {
      PlanarOpenLoop open_loop(scene);
      open_loop.scan_faults(planar_workspace_grid(scene, kPlanarFaultScanStep_m), Vec2{});
      if (auto script = scene_script_check(open_loop.faults(), options.thresholds.max_script_faults,
                                           printf_string("in the open-loop scan (every %g mm of the workspace, at rest)",
                                                         kPlanarFaultScanStep_m * 1e3))) {
        report.scene_checks.push_back(*script);
      }
    }
    script_potential = planar_script_potential(scene);
  } catch (const ScriptsTooSlow& slow) {
    return too_slow(slow.check());
  }
  for (const CheckResult& check : report.scene_checks) report.pass = report.pass && check.pass;
  std::vector<PlanarValidateKind> chosen = kinds;
  if (chosen.empty()) {
    for (std::size_t i = 0; i < std::size(kPlanarValidateNames); ++i) chosen.push_back(static_cast<PlanarValidateKind>(i));
  }
  for (const PlanarValidateKind kind : chosen) {
    const PlanarValidateScenario scenario = build_planar_validate_scenario(kind, scene, options);
    report.scenarios.push_back(run_planar_validate_scenario(scene, scenario, options,
                                                            scene.script_count > 0 ? &script_potential : nullptr));
    report.pass = report.pass && report.scenarios.back().pass;
  }
  return report;
}

std::string free_start_problem(const PlanarScene& scene, const HarnessOptions& options) {
  try {
    (void)planar_joint_angles_at(scene.device, options.free_start_planar_m.value_or(scene.device.home_m));
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace hapscene
