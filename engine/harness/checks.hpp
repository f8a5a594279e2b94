#pragma once
// Verdicts: each measurement of a scenario against its threshold (the environment's
// "validate" block or the defaults).
#include <cstdint>
#include <optional>
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

// The checks of the scene as a whole, listed only when there is something to report (1-D
// and 2-D validate alike): "effects", an effect that can never act (the scene's load
// warnings; always failing), and "script", the faults an open-loop scan of the workspace
// met (`scan` names the scan: "in the force-field scan").
std::optional<CheckResult> scene_effects_check(const std::vector<std::string>& load_warnings);
std::optional<CheckResult> scene_script_check(const ScriptFaultLog& faults, std::uint64_t max_script_faults,
                                              const std::string& scan);

std::vector<CheckResult> judge_scenario(const Scene& scene, const ValidateThresholds& thresholds,
                                        const ForceField& field, const ScenarioMetrics& metrics);

}  // namespace hapscene
