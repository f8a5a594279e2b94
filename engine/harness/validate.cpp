#include "engine/harness/validate.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/stop_request.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {
namespace {

// Records every tick and watches the CPU time of the ticks: a scene whose ticks take
// longer than the period is stopped (the run's stop flag) rather than simulated for hours.
class PacedRecorder final : public TickObserver {
 public:
  PacedRecorder(Recorder* recorder, PaceWatch* pace, std::atomic<bool>* stop)
      : recorder_(recorder), pace_(pace), stop_(stop) {}
  void on_tick(const TickState& s) noexcept override {
    recorder_->on_tick(s);
    if (!pace_->tick()) stop_->store(true, std::memory_order_relaxed);
  }

 private:
  Recorder* recorder_;
  PaceWatch* pace_;
  std::atomic<bool>* stop_;
};

}  // namespace

PassivityBound passivity_bound(const DeviceProfile& device, double period_s) {
  const double sampled_N_per_m = 2.0 * device.plant.viscous_N_s_per_m / period_s;
  const double count_m = std::abs(counts_to_position_m(device, 1.0) - counts_to_position_m(device, 0.0));
  const double quantized_N_per_m = 2.0 * device.plant.coulomb_N / count_m;
  if (quantized_N_per_m < sampled_N_per_m) return {quantized_N_per_m, "2fc/D"};
  return {sampled_N_per_m, "2b/T"};
}

std::string free_start_problem(const Scene& scene, const HarnessOptions& options) {
  const Scenario free = build_scenario(ScenarioKind::free, scene, ForceField{}, options);
  try {
    const SimulatedHapkit device(scene.device, free.simulation);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

ScenarioResult run_scenario(const Scene& scene, const ForceField& field, const Scenario& scenario,
                            const HarnessOptions& options) {
  ScenarioResult result;
  result.scenario = scenario;
  if (!scenario.applicable) return result;

  // The device: the scene's profile, with the sensor noise the options ask for.
  DeviceProfile profile = scene.device;
  if (options.noise_counts >= 0.0) profile.plant.sensor_noise_counts = options.noise_counts;
  SimulatedHapkit device(profile, scenario.simulation);

  // Run in simulated time, recording every tick into memory reserved up front.
  const auto ticks = static_cast<std::size_t>(std::llround(scenario.duration_s * scene.rate_hz));
  Recorder recorder(&device, ticks + 1);
  PaceWatch pace(scene.period_s);
  std::atomic<bool> stop{false};
  PacedRecorder observer(&recorder, &pace, &stop);
  RunOptions run_options{.duration_s = scenario.duration_s, .pacing = Pacing::simulated_time, .stop_requested = &stop};
  const RunSummary summary = run_scene(scene, device, run_options, &observer);
  throw_if_stop_requested();  // the run stopped early on request: nothing to judge

  // Measure and judge (a run stopped for its pace is judged on that alone).
  result.records = recorder.take();
  result.metrics = measure_run(scene, field, result.records, device.x_m(), summary, scenario.watch_from_s);
  if (pace.too_slow()) {
    result.checks = {pace.check(scene)};
  } else {
    result.checks = judge_scenario(scene, options.thresholds, field, result.metrics);
  }
  result.pass = std::all_of(result.checks.begin(), result.checks.end(),
                            [](const CheckResult& c) { return c.pass; });
  return result;
}

ValidationReport validate_scene(const Scene& scene, const std::vector<ScenarioKind>& kinds,
                                const HarnessOptions& options) {
  ValidationReport report;
  report.scene_name = scene.name;
  report.source_path = scene.source_path;
  report.rate_hz = scene.rate_hz;
  const PassivityBound bound = passivity_bound(scene.device, scene.period_s);
  report.passivity_bound_N_per_m = bound.N_per_m;
  report.passivity_bound_name = bound.name;
  report.options = options;
  // Scripts too slow for the loop: nothing else is run (it would take hours). The first
  // calls are timed alone, then the field scan's (scan_force_field).
  const auto too_slow = [&](CheckResult pace) {
    report.load_warnings = scene.load_warnings;
    report.scene_checks.push_back(std::move(pace));
    report.pass = false;
    return report;
  };
  try {
    report.field = scan_force_field(scene, options.thresholds.stiff_threshold_N_per_m);
  } catch (const ScriptsTooSlow& slow) {
    return too_slow(slow.check());
  }
  for (const StiffRegion& region : report.field.regions) {
    report.stiffest_region_N_per_m = std::max(report.stiffest_region_N_per_m, region.stiffness_N_per_m);
  }

  // The scene as a whole: effects that never act, and faults met by the field scan.
  report.load_warnings = scene.load_warnings;
  if (auto effects = scene_effects_check(scene.load_warnings)) report.scene_checks.push_back(*effects);
  if (auto script = scene_script_check(report.field.faults, options.thresholds.max_script_faults,
                                       "in the force-field scan")) {
    report.scene_checks.push_back(*script);
  }
  for (const CheckResult& check : report.scene_checks) report.pass = report.pass && check.pass;

  std::vector<ScenarioKind> chosen = kinds;
  if (chosen.empty()) {
    for (std::size_t i = 0; i < std::size(kScenarioNames); ++i) chosen.push_back(static_cast<ScenarioKind>(i));
  }
  for (const ScenarioKind kind : chosen) {
    const Scenario scenario = build_scenario(kind, scene, report.field, options);
    report.scenarios.push_back(run_scenario(scene, report.field, scenario, options));
    report.pass = report.pass && report.scenarios.back().pass;
  }
  return report;
}

}  // namespace hapscene
