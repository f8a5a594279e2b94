#include "engine/harness/checks.hpp"

#include <cmath>

#include "engine/base/format.hpp"
#include "engine/harness/check_parts.hpp"

namespace hapscene {

CheckResult check_at_most(std::string name, double value, double threshold, std::string unit, std::string detail) {
  return CheckResult{std::move(name), value, threshold, std::move(unit), value <= threshold, std::move(detail)};
}

std::string where_when(double x_m, double t_s) { return printf_string("at %.2f mm, t %.3f s", x_m * 1e3, t_s); }

std::string where_when(const Vec2& x_m, double t_s) {
  return printf_string("at (%.2f, %.2f) mm, t %.3f s", x_m[0] * 1e3, x_m[1] * 1e3, t_s);
}

CheckResult passivity_check(const PassivityMetrics& p, const ValidateThresholds& t) {
  CheckResult passivity = check_at_most(
      "passivity", p.ratio, t.max_passivity_ratio, "",
      printf_string("created %.3g mJ, dissipated %.3g mJ, net %.3g mJ%s", p.created_J * 1e3, p.dissipated_J * 1e3,
                    p.net_J * 1e3, p.grows ? ", growing" : ""));
  // Too little energy created to weigh (a negative ratio: the rendering absorbed energy):
  // not judged, which does not fail, and says so.
  passivity.judged = p.created_J > kMinJudgedEnergy_J;
  passivity.pass = !passivity.judged || (p.ratio <= t.max_passivity_ratio && !p.grows);
  if (!passivity.judged) passivity.detail += printf_string("; not judged: created at most %g mJ", kMinJudgedEnergy_J * 1e3);
  return passivity;
}

void add_oscillation_checks(const OscillationMetrics& o, const ValidateThresholds& t, const std::string& motion,
                            std::vector<CheckResult>* checks) {
  checks->push_back(check_at_most("limit_cycle", o.residual_amplitude_m, t.max_residual_amplitude_m, "m", motion));
  checks->push_back(check_at_most("growth", o.growth, t.max_amplitude_growth, "", motion));
}

const char* verdict_text(const CheckResult& check) {
  if (!check.judged) return "not judged";
  return check.pass ? "pass" : "FAIL";
}

std::vector<CheckResult> judge_scenario(const Scene& scene, const ValidateThresholds& t,
                                        const ForceField& field, const ScenarioMetrics& m) {
  std::vector<CheckResult> checks;

  // Force: how large, how long at the limit, how fast it changes, how rough.
  add_force_checks(scene, t, m, &checks);
  CheckResult slip = check_at_most(
      "slip", static_cast<double>(m.slip_force_ticks + m.slip_step_ticks),
      static_cast<double>(t.max_slip_ticks), "ticks",
      printf_string("%llu ticks above %g N, %llu with a 1-ms step above %g N (largest %.3f N)",
             static_cast<unsigned long long>(m.slip_force_ticks), scene.device.limits.slip_force_N,
             static_cast<unsigned long long>(m.slip_step_ticks), scene.device.limits.slip_step_N,
             m.max_step_1ms_N));
  if (!slip.pass && m.slip_first_t_s >= 0.0) slip.detail += "; first " + where_when(m.slip_first_x_m, m.slip_first_t_s);
  checks.push_back(slip);

  // Energy: created by the rendering against what the device dissipates on its own.
  CheckResult passivity = passivity_check(m.passivity, t);
  if (!field.behaviour.static_field()) {
    passivity.detail += "; stored energy from the field at rest (" + field.behaviour.note + ")";
  }
  checks.push_back(passivity);

  // Oscillation in the watch window (after the hand lets go, or while it holds still).
  if (m.oscillation) {
    const OscillationMetrics& o = *m.oscillation;
    const std::string motion =
        printf_string("from %.2f s: %d half-cycles at %.2f Hz around %.2f mm, initial %.3f mm", o.from_s,
               o.half_cycles, o.frequency_Hz, o.rest_m * 1e3, o.initial_amplitude_m * 1e3);
    add_oscillation_checks(o, t, motion, &checks);
  }

  // Walls: how deep the handle went past an edge the harness found.
  bool has_edges = false;
  for (const StiffRegion& region : field.regions) has_edges = has_edges || region.low_is_edge || region.high_is_edge;
  if (has_edges) {
    checks.push_back(check_at_most("penetration", m.max_penetration_m, t.max_penetration_m, "m",
                                   printf_string("deepest at %.2f mm", m.max_penetration_x_m * 1e3)));
  }

  // Grit, scripts and timing.
  add_jitter_script_and_timing_checks(scene, t, m, "rms second difference of the commanded force", &checks);
  return checks;
}

std::optional<CheckResult> scene_effects_check(const std::vector<std::string>& load_warnings) {
  if (load_warnings.empty()) return std::nullopt;
  std::string detail;
  for (const std::string& warning : load_warnings) detail += (detail.empty() ? "" : "; ") + warning;
  return CheckResult{"effects", static_cast<double>(load_warnings.size()), 0.0, "effects", false, detail};
}

std::optional<CheckResult> scene_script_check(const ScriptFaultLog& faults, std::uint64_t max_script_faults,
                                              const std::string& scan) {
  if (faults.empty()) return std::nullopt;
  const std::vector<std::string>& lines = faults.lines();
  std::string detail = scan + ": " + lines[0];
  for (std::size_t i = 1; i < lines.size(); ++i) detail += "; " + lines[i];
  const auto count = static_cast<double>(lines.size());
  const auto allowed = static_cast<double>(max_script_faults);
  return CheckResult{"script", count, allowed, "faults", count <= allowed, detail};
}

}  // namespace hapscene
