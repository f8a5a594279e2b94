#pragma once
// Test specs for 2-DOF (planar) environments (docs/reference/test-specs.md, "Test specs in 2-D"): the 1-D format
// with vectors. `forces` at points "at": [x, y] with "v": [vx, vy] and "force": [fx, fy]
// (tolerance on the magnitude of the difference), `zero_outside` a box region, and
// `never_exceeds` over a grid of the workspace, all open loop as the 2-D `probe` computes
// them; every script fault in the workspace, at rest, in motion or later in time, fails
// the spec. The closed-loop expectations (`passes_validate`, `scenarios`) are parsed here
// and judged by closed_loop_outcomes_2d.
#include <optional>
#include <string>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/harness/planar_open_loop.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/harness/test_spec.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// The grid the 2-D region checks and the scans for faults use: every 1 mm of the
// workspace box, on both axes.
inline constexpr double kPlanarSpecGridStep_m = kPlanarFaultScanStep_m;

// A scenario expectation of a 2-D spec, as written: the keys of the 1-D ones (docs/reference/
// test-specs.md); the scenario's name and the check names in `fail` are not checked
// against a list here (2-D validate names its own).
struct PlanarScenarioExpectation {
  std::string pointer;  // "/scenarios/0"
  std::string scenario;
  std::optional<int> min_half_cycles, max_half_cycles;
  std::optional<std::pair<double, double>> frequency_Hz;
  std::optional<double> max_force_N;
  std::optional<bool> pass;
  std::vector<std::string> fail;
};

// What a 2-D spec expects of closed-loop runs (validate).
struct PlanarClosedLoopExpectations {
  HarnessOptions options;     // "options": the hand, noise, seed
  std::optional<Vec2> start_m;  // "options/start": [x, y]
  std::optional<bool> passes_validate;
  std::vector<PlanarScenarioExpectation> scenarios;
  bool empty() const { return !passes_validate && scenarios.empty(); }
};

// Judges the closed-loop expectations of a 2-D spec on its scene (`thresholds`: its
// environment's "validate" block): one outcome per expectation ("/passes_validate",
// "/scenarios/N/..."), and each script fault met in the runs in `faults` (message, then
// the line to print): one run of 2-D validate (all seven scenarios) with the spec's options
// and the environment's "validate" thresholds.
std::vector<SpecOutcome> closed_loop_outcomes_2d(const PlanarScene& scene, const ValidateThresholds& thresholds,
                                                 const PlanarClosedLoopExpectations& expectations,
                                                 std::vector<std::pair<std::string, std::string>>* faults);

// Runs a spec whose environment is planar into `result` (run_test_spec calls it):
// InputError, located, for anything invalid in the spec or its environment;
// ScriptsTooSlow when a scan finds the scripts too slow for the loop's checks.
void run_planar_test_spec(const std::string& spec_path, SpecResult* result);

}  // namespace hapscene
