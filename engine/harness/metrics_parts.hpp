#pragma once
// What the 1-D and the 2-D validate measure alike from a run's tick records
// (metrics.cpp, planar_metrics.cpp): the force's size, time at the limit, slew and jitter
// (forces by their magnitude, norm(): |F| in 1-D), and the scripts' faults and tick
// times from the run summary. `Metrics` is ScenarioMetrics or PlanarScenarioMetrics,
// `Record` TickRecord or PlanarValidateRecord (a position is a number in 1-D, a Vec2 in
// 2-D). Internal to the harness.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/base/format.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

// Where a script faulted, for its message: "x 10.02 mm", "at (10.02, 130.00) mm".
inline std::string fault_position_text(double x_m) { return printf_string("x %.2f mm", x_m * 1e3); }
inline std::string fault_position_text(const Vec2& x_m) {
  return printf_string("at (%.2f, %.2f) mm", x_m[0] * 1e3, x_m[1] * 1e3);
}

// max_requested_N, max_output_N (where and when), time_at_limit_s and its fraction (at
// `limit_N`), max_slew_N_per_s, force_jitter_N and jitter_peak_N (where and when).
template <typename Record, typename Metrics>
void measure_force_trace(const std::vector<Record>& records, double limit_N, double period_s, Metrics* m) {
  std::uint64_t at_limit_ticks = 0;
  double jitter_sum_N2 = 0.0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const Record& r = records[k];
    const double output_N = norm(r.output_N);
    m->max_requested_N = std::max(m->max_requested_N, norm(r.requested_N));
    if (output_N > m->max_output_N) {
      m->max_output_N = output_N;
      m->max_output_x_m = r.x_true_m;
      m->max_output_t_s = r.t_s;
    }
    if (output_N >= limit_N * (1.0 - 1e-12)) ++at_limit_ticks;
    if (k > 0) m->max_slew_N_per_s = std::max(m->max_slew_N_per_s, norm(r.output_N - records[k - 1].output_N) / period_s);
    // The second difference of the commanded force, F[k] - (F[k-1] + F[k+1]) / 2.
    if (k > 0 && k + 1 < records.size()) {
      const double second_N = norm(r.output_N - 0.5 * (records[k - 1].output_N + records[k + 1].output_N));
      jitter_sum_N2 += second_N * second_N;
      if (second_N > m->jitter_peak_N) {
        m->jitter_peak_N = second_N;
        m->jitter_peak_x_m = r.x_true_m;
        m->jitter_peak_t_s = r.t_s;
      }
    }
  }
  m->time_at_limit_s = static_cast<double>(at_limit_ticks) * period_s;
  m->time_at_limit_fraction =
      records.empty() ? 0.0 : static_cast<double>(at_limit_ticks) / static_cast<double>(records.size());
  if (records.size() > 2) m->force_jitter_N = std::sqrt(jitter_sum_N2 / static_cast<double>(records.size() - 2));
}

// script_errors, script_budget_overruns, script_faults (each disabled script's message,
// with when and where it faulted: the faulting call was the last one before the skipped
// ones, one call per tick, so the trace gives the true position as well as the time),
// the compute times and the safety counters, from the run's summary.
template <int N, typename Record, typename Metrics>
void measure_scripts_and_timing(const RunSummaryOf<N>& summary, const std::vector<Record>& records, Metrics* m) {
  m->script_errors = summary.script_errors;
  m->script_budget_overruns = summary.script_budget_overruns;
  for (const ScriptReport& script : summary.scripts) {
    if (!script.disabled) continue;
    if (script.skipped_calls < records.size()) {
      const Record& at = records[records.size() - 1 - script.skipped_calls];
      m->script_faults.push_back({script.fault, printf_string("t %.3f s, ", at.t_s) + fault_position_text(at.x_true_m)});
    } else {
      m->script_faults.push_back({script.fault, ""});
    }
  }
  m->compute_p50_s = static_cast<double>(summary.compute_ns.percentile_ns(0.50)) * 1e-9;
  m->compute_p99_s = static_cast<double>(summary.compute_ns.percentile_ns(0.99)) * 1e-9;
  m->compute_max_s = static_cast<double>(summary.compute_ns.max_ns()) * 1e-9;
  m->safety = summary.safety;
}

}  // namespace hapscene
