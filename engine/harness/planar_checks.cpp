#include "engine/harness/planar_checks.hpp"

#include <cmath>

#include "engine/base/format.hpp"

namespace hapscene {
namespace {

CheckResult at_most(std::string name, double value, double threshold, std::string unit, std::string detail) {
  return CheckResult{std::move(name), value, threshold, std::move(unit), value <= threshold, std::move(detail)};
}

std::string at_point(const Vec2& x_m) { return printf_string("at (%.2f, %.2f) mm", x_m[0] * 1e3, x_m[1] * 1e3); }

std::string where_when(const Vec2& x_m, double t_s) { return at_point(x_m) + printf_string(", t %.3f s", t_s); }

std::string shape_name(const std::vector<PlanarShapeGeometry>& shapes, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= shapes.size()) return "shape";
  return printf_string("%s %d", planar_shape_kind_name(shapes[static_cast<std::size_t>(index)].kind), index);
}

}  // namespace

std::vector<CheckResult> judge_planar_scenario(const PlanarScene& scene, const ValidateThresholds& t,
                                               const std::vector<PlanarShapeGeometry>& shapes,
                                               const PlanarScenarioMetrics& m) {
  std::vector<CheckResult> checks;

  // Force: its magnitude, time at the limit, how fast the vector changes.
  const double max_force_N = t.max_force_N > 0.0 ? t.max_force_N : scene.safety.max_force_N;
  checks.push_back(at_most("max_force", m.max_output_N, max_force_N, "N",
                           where_when(m.max_output_x_m, m.max_output_t_s) +
                               printf_string(" (asked up to %.3f N)", m.max_requested_N)));
  checks.push_back(at_most("time_at_limit", m.time_at_limit_fraction, t.max_time_at_limit_fraction, "",
                           printf_string("%.3f s of %.3f s at %g N", m.time_at_limit_s, m.duration_s,
                                         scene.safety.max_force_N)));
  const double max_slew = t.max_slew_N_per_s > 0.0 ? t.max_slew_N_per_s : scene.safety.slew_limit_N_per_s;
  CheckResult slew = at_most("slew", m.max_slew_N_per_s, max_slew, "N/s",
                             printf_string("slew limiter acted on %llu ticks",
                                           static_cast<unsigned long long>(m.safety.slew_limited_ticks)));
  slew.pass = m.max_slew_N_per_s < max_slew * (1.0 - 1e-9);
  checks.push_back(slew);

  // Energy: created by the rendering against the joints' own viscous loss.
  const PassivityMetrics& p = m.passivity;
  CheckResult passivity = at_most(
      "passivity", p.ratio, t.max_passivity_ratio, "",
      printf_string("created %.3g mJ, dissipated %.3g mJ, net %.3g mJ%s", p.created_J * 1e3, p.dissipated_J * 1e3,
                    p.net_J * 1e3, p.grows ? ", growing" : ""));
  passivity.judged = p.created_J > kMinJudgedEnergy_J;
  passivity.pass = !passivity.judged || (p.ratio <= t.max_passivity_ratio && !p.grows);
  if (!passivity.judged) passivity.detail += printf_string("; not judged: created at most %g mJ", kMinJudgedEnergy_J * 1e3);
  checks.push_back(passivity);

  // Oscillation in the watch window.
  if (m.oscillation) {
    const OscillationMetrics& o = *m.oscillation;
    const std::string motion =
        printf_string("from %.2f s: %d half-cycles at %.2f Hz around (%.2f, %.2f) mm along (%.2f, %.2f), initial %.3f mm",
                      o.from_s, o.half_cycles, o.frequency_Hz, m.rest_m[0] * 1e3, m.rest_m[1] * 1e3, m.major_axis[0],
                      m.major_axis[1], o.initial_amplitude_m * 1e3);
    checks.push_back(at_most("limit_cycle", o.residual_amplitude_m, t.max_residual_amplitude_m, "m", motion));
    checks.push_back(at_most("growth", o.growth, t.max_amplitude_growth, "", motion));
  }

  // Shapes: how deep into a solid, and whether the rendering let the handle through one.
  if (!shapes.empty()) {
    checks.push_back(at_most("penetration", m.max_penetration_m, t.max_penetration_m, "m",
                             m.max_penetration_shape < 0
                                 ? std::string("never inside a solid")
                                 : "deepest into the " + shape_name(shapes, m.max_penetration_shape) + " " +
                                       where_when(m.max_penetration_x_m, m.max_penetration_t_s)));
    CheckResult pop = at_most("pop_through", static_cast<double>(m.pop_throughs),
                              static_cast<double>(t.max_pop_through), "crossings",
                              "crossings of a solid not held back by the rendering");
    if (m.pop_throughs > 0) {
      pop.detail += "; first through the " + shape_name(shapes, m.first_pop_shape) + " " +
                    where_when(m.first_pop_x_m, m.first_pop_t_s);
    }
    checks.push_back(pop);
  }

  // Singularity: force asked for where the pose made the safety stage hold it.
  checks.push_back(at_most(
      "singularity", static_cast<double>(m.pose_hold_force_ticks), static_cast<double>(t.max_singularity_ticks),
      "ticks",
      printf_string("pose held on %llu ticks (%llu with force asked); largest condition number %.1f of limit %g ",
                    static_cast<unsigned long long>(m.pose_hold_ticks),
                    static_cast<unsigned long long>(m.pose_hold_force_ticks), m.max_condition,
                    scene.device_model.condition_limit) +
          where_when(m.max_condition_x_m, m.max_condition_t_s)));

  // Grit, scripts and timing.
  CheckResult jitter = at_most("jitter", m.force_jitter_N, t.max_force_jitter_N, "N",
                               "rms second difference of the commanded force vector");
  if (!jitter.pass) jitter.detail += printf_string("; largest %.3f N ", m.jitter_peak_N) + where_when(m.jitter_peak_x_m, m.jitter_peak_t_s);
  checks.push_back(jitter);
  CheckResult script = at_most("script", static_cast<double>(m.script_errors + m.script_budget_overruns),
                               static_cast<double>(t.max_script_faults), "faults",
                               printf_string("%llu errors, %llu budget overruns",
                                             static_cast<unsigned long long>(m.script_errors),
                                             static_cast<unsigned long long>(m.script_budget_overruns)));
  for (std::size_t i = 0; i < m.script_faults.size(); ++i) script.detail += (i == 0 ? ": " : "; ") + m.script_faults[i].text();
  checks.push_back(script);
  const double max_compute_s = t.max_tick_compute_s > 0.0 ? t.max_tick_compute_s : 0.5 * scene.period_s;
  checks.push_back(at_most("tick_compute", m.compute_p99_s, max_compute_s, "s",
                           printf_string("p50 %.2f us, p99 %.2f us, max %.2f us", m.compute_p50_s * 1e6,
                                         m.compute_p99_s * 1e6, m.compute_max_s * 1e6)));
  return checks;
}

}  // namespace hapscene
