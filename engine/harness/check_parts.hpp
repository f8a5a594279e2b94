#pragma once
// The checks the 1-D and the 2-D validate judge alike (checks.cpp, planar_checks.cpp):
// the force's size, time at the limit and slew, passivity, oscillation, jitter, scripts
// and tick time, over the metrics of either dimension (ScenarioMetrics,
// PlanarScenarioMetrics: a position is a number in 1-D, a Vec2 in 2-D). Internal to the
// harness.
#include <string>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/base/format.hpp"
#include "engine/harness/checks.hpp"
#include "engine/load/validate_thresholds.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// A check that passes when value <= threshold.
CheckResult check_at_most(std::string name, double value, double threshold, std::string unit, std::string detail);

// Where and when, for a failing check: "at 12.00 mm, t 0.512 s", "at (1.00, 130.00) mm, t 0.512 s".
std::string where_when(double x_m, double t_s);
std::string where_when(const Vec2& x_m, double t_s);

// "max_force", "time_at_limit" and "slew" (reaching the slew limiter fails).
template <int N, class Metrics>
void add_force_checks(const SceneOf<N>& scene, const ValidateThresholds& t, const Metrics& m,
                      std::vector<CheckResult>* checks) {
  const double max_force_N = t.max_force_N > 0.0 ? t.max_force_N : scene.safety.max_force_N;
  checks->push_back(check_at_most("max_force", m.max_output_N, max_force_N, "N",
                                  where_when(m.max_output_x_m, m.max_output_t_s) +
                                      printf_string(" (asked up to %.3f N)", m.max_requested_N)));
  checks->push_back(check_at_most("time_at_limit", m.time_at_limit_fraction, t.max_time_at_limit_fraction, "",
                                  printf_string("%.3f s of %.3f s at %g N", m.time_at_limit_s, m.duration_s,
                                                scene.safety.max_force_N)));
  const double max_slew = t.max_slew_N_per_s > 0.0 ? t.max_slew_N_per_s : scene.safety.slew_limit_N_per_s;
  CheckResult slew = check_at_most("slew", m.max_slew_N_per_s, max_slew, "N/s",
                                   printf_string("slew limiter acted on %llu ticks",
                                                 static_cast<unsigned long long>(m.safety.slew_limited_ticks)));
  slew.pass = m.max_slew_N_per_s < max_slew * (1.0 - 1e-9);
  checks->push_back(slew);
}

// "passivity": created against dissipated energy; not judged (and not failing) when at
// most kMinJudgedEnergy_J was created.
CheckResult passivity_check(const PassivityMetrics& p, const ValidateThresholds& t);

// "limit_cycle" and "growth" of the oscillation, each with `motion` as its detail.
void add_oscillation_checks(const OscillationMetrics& o, const ValidateThresholds& t, const std::string& motion,
                            std::vector<CheckResult>* checks);

// "jitter" (`what`: the rms second difference of what), "script" and "tick_compute".
template <int N, class Metrics>
void add_jitter_script_and_timing_checks(const SceneOf<N>& scene, const ValidateThresholds& t, const Metrics& m,
                                         const std::string& what, std::vector<CheckResult>* checks) {
  CheckResult jitter = check_at_most("jitter", m.force_jitter_N, t.max_force_jitter_N, "N", what);
  if (!jitter.pass) {
    jitter.detail += printf_string("; largest %.3f N ", m.jitter_peak_N) + where_when(m.jitter_peak_x_m, m.jitter_peak_t_s);
  }
  checks->push_back(jitter);
  CheckResult script = check_at_most("script", static_cast<double>(m.script_errors + m.script_budget_overruns),
                                     static_cast<double>(t.max_script_faults), "faults",
                                     printf_string("%llu errors, %llu budget overruns",
                                                   static_cast<unsigned long long>(m.script_errors),
                                                   static_cast<unsigned long long>(m.script_budget_overruns)));
  for (std::size_t i = 0; i < m.script_faults.size(); ++i) script.detail += (i == 0 ? ": " : "; ") + m.script_faults[i].text();
  checks->push_back(script);
  const double max_compute_s = t.max_tick_compute_s > 0.0 ? t.max_tick_compute_s : 0.5 * scene.period_s;
  checks->push_back(check_at_most("tick_compute", m.compute_p99_s, max_compute_s, "s",
                                  printf_string("p50 %.2f us, p99 %.2f us, max %.2f us", m.compute_p50_s * 1e6,
                                                m.compute_p99_s * 1e6, m.compute_max_s * 1e6)));
}

}  // namespace hapscene
