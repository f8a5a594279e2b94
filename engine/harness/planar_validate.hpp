#pragma once
// `hapscene validate` on a 2-DOF (planar) scene as a library call: build the 2-D
// scenarios (planar_validate_scenario.hpp), run each closed loop on the simulated planar
// device with the 2-D virtual hand in simulated time, measure (planar_metrics.hpp) and
// judge (planar_checks.hpp); beside them, the device's stiffness bound per pose
// (planar_bound.hpp). The 1-D twin is validate.hpp.
#include <string>
#include <vector>

#include "engine/harness/checks.hpp"
#include "engine/harness/planar_bound.hpp"
#include "engine/harness/planar_checks.hpp"
#include "engine/harness/planar_metrics.hpp"
#include "engine/harness/planar_validate_scenario.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct PlanarScenarioResult {
  PlanarValidateScenario scenario;
  PlanarScenarioMetrics metrics;
  std::vector<CheckResult> checks;          // empty when not applicable
  std::vector<PlanarValidateRecord> records;  // every tick, for the figure
  std::vector<Vec2> proxies_m;              // records.size() x shapes
  bool pass{true};
};

struct PlanarValidationReport {
  std::string scene_name;
  std::string source_path;
  double rate_hz{};
  PlanarStiffnessBound bound;               // per pose over the workspace
  std::size_t shapes{};                     // the scene's walls, boxes, circles, polygons and scripts' shapes
  std::size_t scripts{};                    // the scene's script effects (their stiffness is not known)
  HarnessOptions options;
  std::vector<PlanarScenarioResult> scenarios;
  std::vector<CheckResult> scene_checks;    // "effects" (an effect that never acts), when failing
  std::vector<std::string> load_warnings;
  bool pass{true};
};

// Runs one scenario (deterministic: the same inputs give bit-identical records). Throws
// InputError when the linkage cannot reach the scenario's start. `script_potential`: the
// scripts' stored energy for the passivity observer (planar_script_potential.hpp; none
// credited when null).
PlanarScenarioResult run_planar_validate_scenario(const PlanarScene& scene, const PlanarValidateScenario& scenario,
                                                  const HarnessOptions& options,
                                                  const PlanarScriptPotential* script_potential = nullptr);

// Why the free scenario cannot start where `options` put it (the profile's home when
// unset): the linkage cannot put its handle there. Empty when it can (validate.hpp's
// free_start_problem, for two axes).
std::string free_start_problem(const PlanarScene& scene, const HarnessOptions& options);

// Runs the given scenarios (all seven when `kinds` is empty), with the scripts' stored
// energy from planar_script_potential.
PlanarValidationReport validate_planar_scene(const PlanarScene& scene, const std::vector<PlanarValidateKind>& kinds,
                                             const HarnessOptions& options);

}  // namespace hapscene
