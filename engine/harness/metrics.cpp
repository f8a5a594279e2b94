#include "engine/harness/metrics.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/format.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/harness/metrics_parts.hpp"

namespace hapscene {
namespace {

PassivityMetrics measure_passivity(const Scene& scene, const ForceField& field,
                                   const std::vector<TickRecord>& records, double final_x_m) {
  PassivityMetrics p;
  const double b_N_s_per_m = scene.device.plant.viscous_N_s_per_m;
  const double period_s = scene.period_s;
  const std::size_t n = records.size();
  if (n == 0) return p;
  const double start_potential_J = field.potential_at_J(records[0].x_true_m);
  double net_at_half_J = 0.0;
  // Work of the held motor force over each tick, and the device's loss while pushed.
  for (std::size_t k = 0; k < n; ++k) {
    const double next_x_m = k + 1 < n ? records[k + 1].x_true_m : final_x_m;
    const double dx_m = next_x_m - records[k].x_true_m;
    p.motor_work_J += records[k].motor_N * dx_m;
    if (records[k].motor_N != 0.0) p.dissipated_J += b_N_s_per_m * dx_m * dx_m / period_s;
    if (k + 1 == n / 2) {
      const double stored_J = field.potential_at_J(next_x_m) - start_potential_J;
      net_at_half_J = p.motor_work_J + stored_J - p.dissipated_J;
    }
  }
  p.stored_J = field.potential_at_J(final_x_m) - start_potential_J;
  p.created_J = p.motor_work_J + p.stored_J;
  p.net_J = p.created_J - p.dissipated_J;
  p.ratio = p.dissipated_J > 0.0 ? p.created_J / p.dissipated_J : 0.0;
  p.grows = p.net_J > kMinJudgedEnergy_J && p.net_J > net_at_half_J;
  return p;
}

}  // namespace

OscillationMetrics measure_oscillation(const std::vector<TickRecord>& records, double from_s,
                                       double band_m) {
  OscillationMetrics o;
  o.from_s = from_s;
  const auto first = std::find_if(records.begin(), records.end(),
                                  [&](const TickRecord& r) { return r.t_s >= from_s; });
  const auto count = static_cast<std::size_t>(records.end() - first);
  if (count < 10) return o;
  const auto tail = first + static_cast<std::ptrdiff_t>(count - count * 3 / 10);
  const auto head_end = first + static_cast<std::ptrdiff_t>(count / 5);

  // Rest position and residual amplitude from the last 30 %.
  double sum_m = 0.0;
  double low_m = INFINITY;
  double high_m = -INFINITY;
  for (auto it = tail; it != records.end(); ++it) {
    sum_m += it->x_true_m;
    low_m = std::min(low_m, it->x_true_m);
    high_m = std::max(high_m, it->x_true_m);
  }
  o.rest_m = sum_m / static_cast<double>(records.end() - tail);
  o.residual_amplitude_m = 0.5 * (high_m - low_m);
  for (auto it = first; it != head_end; ++it) {
    o.initial_amplitude_m = std::max(o.initial_amplitude_m, std::abs(it->x_true_m - o.rest_m));
  }
  o.growth = o.initial_amplitude_m > band_m ? o.residual_amplitude_m / o.initial_amplitude_m
             : o.residual_amplitude_m > band_m ? INFINITY : 0.0;

  // Crossings of the rest position, leaving the band on the other side.
  int side = 0;
  double first_cross_s = 0.0;
  double last_cross_s = 0.0;
  for (auto it = first; it != records.end(); ++it) {
    const double offset_m = it->x_true_m - o.rest_m;
    const int now = offset_m > band_m ? 1 : (offset_m < -band_m ? -1 : 0);
    if (now == 0) continue;
    if (side != 0 && now != side) {
      if (o.half_cycles == 0) first_cross_s = it->t_s;
      last_cross_s = it->t_s;
      ++o.half_cycles;
    }
    side = now;
  }
  if (o.half_cycles >= 2 && last_cross_s > first_cross_s) {
    o.frequency_Hz = (o.half_cycles - 1) / (2.0 * (last_cross_s - first_cross_s));
  }
  return o;
}

ScenarioMetrics measure_run(const Scene& scene, const ForceField& field,
                            const std::vector<TickRecord>& records, double final_x_m,
                            const RunSummary& summary, std::optional<double> watch_from_s) {
  ScenarioMetrics m;
  m.ticks = records.size();
  m.duration_s = static_cast<double>(records.size()) * scene.period_s;
  const auto ticks_per_ms = static_cast<std::size_t>(std::max(1.0, std::round(1e-3 / scene.period_s)));

  // Force, slew and jitter; then slip and penetration, tick by tick.
  measure_force_trace(records, scene.safety.max_force_N, scene.period_s, &m);
  for (std::size_t k = 0; k < records.size(); ++k) {
    const TickRecord& r = records[k];
    bool slip = false;
    if (std::abs(r.output_N) > scene.device.limits.slip_force_N) {
      ++m.slip_force_ticks;
      slip = true;
    }
    if (k >= ticks_per_ms) {
      const double step_N = std::abs(r.output_N - records[k - ticks_per_ms].output_N);
      m.max_step_1ms_N = std::max(m.max_step_1ms_N, step_N);
      if (step_N > scene.device.limits.slip_step_N) {
        ++m.slip_step_ticks;
        slip = true;
      }
    }
    if (slip && m.slip_first_t_s < 0.0) {
      m.slip_first_t_s = r.t_s;
      m.slip_first_x_m = r.x_true_m;
    }
    const double depth_m = field.penetration_m(r.x_true_m);
    if (depth_m > m.max_penetration_m) {
      m.max_penetration_m = depth_m;
      m.max_penetration_x_m = r.x_true_m;
    }
  }

  // Energy and oscillation.
  m.passivity = measure_passivity(scene, field, records, final_x_m);
  if (watch_from_s) {
    const double per_count_m =
        std::abs(counts_to_position_m(scene.device, 0.0) - counts_to_position_m(scene.device, 1.0));
    m.oscillation = measure_oscillation(records, *watch_from_s, 3.0 * per_count_m);
  }

  // Scripts and timing from the run summary.
  measure_scripts_and_timing(summary, records, &m);
  return m;
}

}  // namespace hapscene
