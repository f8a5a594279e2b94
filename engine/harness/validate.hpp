#pragma once
// `hapscene validate` as a library call: probe the force field, build the scenarios,
// run each closed loop on the simulated Hapkit in simulated time, measure and judge.
#include <vector>

#include "engine/harness/checks.hpp"
#include "engine/harness/force_field.hpp"
#include "engine/harness/metrics.hpp"
#include "engine/harness/recorder.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct ScenarioResult {
  Scenario scenario;
  ScenarioMetrics metrics;
  std::vector<CheckResult> checks;   // empty when the scenario is not applicable
  std::vector<TickRecord> records;   // every tick, for plots
  bool pass{true};
};

struct ValidationReport {
  std::string scene_name;
  std::string source_path;
  double rate_hz{};
  double passivity_bound_N_per_m{};  // min(2 b / T, 2 f_c / D) for this device (passivity_bound)
  const char* passivity_bound_name{"2b/T"};  // which of the two binds
  double stiffest_region_N_per_m{};  // the stiffest region the probe found (0: none)
  HarnessOptions options;
  ForceField field;
  std::vector<ScenarioResult> scenarios;
  // Checks of the scene as a whole, listed only when they fail: "effects" (an effect that
  // can never act inside the workspace, see Scene::load_warnings) and "script" (a script
  // fault met by the open-loop force-field scan), and "pace" (scripts too slow for the
  // loop: see pace.hpp; then nothing else is run and `scenarios` is empty).
  std::vector<CheckResult> scene_checks;
  std::vector<std::string> load_warnings;  // the scene's, for the JSON report
  bool pass{true};
};

// The stiffest passive sampled wall for `device` at `period_s` (Abbott and Okamura): the
// smaller of 2 b / T (Colgate and Schenkel) and 2 f_c / D (D one sensor count), and its name.
struct PassivityBound {
  double N_per_m{};
  const char* name{};
};
PassivityBound passivity_bound(const DeviceProfile& device, double period_s);

// Empty when the free scenario can start at options.free_start_m on the scene's device,
// else why not (outside the sensor's home period, where the board starts counting).
std::string free_start_problem(const Scene& scene, const HarnessOptions& options);

// Runs one scenario (deterministic: the same inputs give bit-identical records).
ScenarioResult run_scenario(const Scene& scene, const ForceField& field, const Scenario& scenario,
                            const HarnessOptions& options);

// Runs the given scenarios (all six when `kinds` is empty).
ValidationReport validate_scene(const Scene& scene, const std::vector<ScenarioKind>& kinds,
                                const HarnessOptions& options);

}  // namespace hapscene
