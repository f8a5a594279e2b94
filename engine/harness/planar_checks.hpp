#pragma once
// Verdicts of a 2-DOF validate run: each measurement against its threshold (the planar
// environment's "validate" block or the defaults). The 1-D checks where they apply, with
// vectors (forces by magnitude), and two of 2-D's own:
//   pop_through  crossings of a shape's solid the rendering let through (count_pop_throughs)
//   singularity  ticks the effects asked for force while the safety stage held it for the
//                pose (the Jacobian's condition number past the profile's condition_limit,
//                or a pose the linkage cannot take); the detail gives the closest approach
// `slip` is not run (planar profiles give no slip force or step).
#include <vector>

#include "engine/harness/checks.hpp"
#include "engine/harness/planar_metrics.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/load/validate_thresholds.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// The names of every 2-D check, in report order (the 1-D list, checks.hpp, is unchanged).
inline constexpr const char* kPlanarCheckNames[] = {
    "max_force",   "time_at_limit", "slew",        "passivity", "limit_cycle", "growth", "penetration",
    "pop_through", "singularity",   "jitter",      "script",    "tick_compute"};

std::vector<CheckResult> judge_planar_scenario(const PlanarScene& scene, const ValidateThresholds& thresholds,
                                               const std::vector<PlanarShapeGeometry>& shapes,
                                               const PlanarScenarioMetrics& metrics);

}  // namespace hapscene
