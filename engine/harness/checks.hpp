#pragma once
// Verdicts: each measurement of a scenario against its threshold (the environment's
// "validate" block or the defaults).
#include <string>
#include <vector>

#include "engine/harness/metrics.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/load/validate_thresholds.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct CheckResult {
  std::string name;        // stable identifier: "max_force", "passivity", ...
  double value{};          // the measurement, in SI (unit below)
  double threshold{};      // the value must be <= threshold (< for "slew")
  std::string unit;        // "N", "N/s", "m", "s", "" (ratio), "ticks"
  bool pass{};
  std::string detail;      // where/when, and the numbers behind the value
  // false: the measurement was too small to judge (passivity below kMinJudgedEnergy_J):
  // shown as "not judged"; it does not fail the run (pass stays true).
  bool judged{true};
};

// The names of every check, in report order.
inline constexpr const char* kCheckNames[] = {
    "max_force", "time_at_limit", "slew",   "slip",   "passivity",      "limit_cycle",
    "growth",    "penetration",   "jitter", "script", "tick_compute"};

// "pass", "FAIL" or "not judged".
const char* verdict_text(const CheckResult& check);

std::vector<CheckResult> judge_scenario(const Scene& scene, const ValidateThresholds& thresholds,
                                        const ForceField& field, const ScenarioMetrics& metrics);

}  // namespace hapscene
