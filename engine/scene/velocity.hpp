#pragma once
// Velocity estimators from the quantized handle position. Each is a named, swappable part:
// the environment picks one ("velocity": {"estimator": "hapkit2019"}) and a scene whose
// effects never read velocity runs none.
#include <string_view>

#include "engine/base/axes.hpp"

namespace hapscene {

enum class VelocityEstimatorKind {
  hapkit2019,   // 0.9 * (x - x1) / T + 0.1 * (x1 - x2) / T: the Hapkit reference sketch
                // (2019+) averages the new and the previous raw difference
  hapkit2013,   // double pole at 0.95 on (x - x1) / T (Hapkit reference sketch, 2013)
  difference,   // (x - x1) / T, unfiltered
  lowpass,      // (x - x1) / T through a first-order low-pass at cutoff_Hz
};

struct VelocityEstimatorConfig {
  VelocityEstimatorKind kind{VelocityEstimatorKind::hapkit2019};
  double cutoff_Hz{100.0};   // lowpass only
  double lowpass_alpha{};    // 1 - exp(-2 pi cutoff T), computed once by lowpass_alpha_for()
};

// The low-pass smoothing factor for a cutoff and a tick period.
double lowpass_alpha_for(double cutoff_Hz, double period_s) noexcept;

// Per-run estimator state, for N axes (each axis filtered alike).
template <int N>
struct VelocityStateOf {
  bool started{};
  Axes<N> previous_x_m{};
  Axes<N> previous_difference_m_per_s{};  // (x1 - x2) / T (hapkit2019)
  Axes<N> v1_m_per_s{};  // previous estimate
  Axes<N> v2_m_per_s{};  // estimate before that (hapkit2013)
};

using VelocityState = VelocityStateOf<1>;

// The names accepted in environment files, in VelocityEstimatorKind order.
inline constexpr std::string_view kVelocityEstimatorNames[] = {"hapkit2019", "hapkit2013",
                                                               "difference", "lowpass"};

// One estimator step: new velocity from the new position. The first call returns 0.
// (Inline, whole: it runs every tick of a scene that reads velocity, and a tick that calls
// nothing saves no registers.)
template <int N>
[[gnu::always_inline]] inline Axes<N> estimate_velocity(const VelocityEstimatorConfig& config, double rate_hz,
                                 const Axes<N>& x_m, VelocityStateOf<N>* state) noexcept {
  if (!state->started) {
    state->started = true;
    state->previous_x_m = x_m;
    return Axes<N>{};
  }
  // (x - x1) / T as (x - x1) * rate: the rate is the number the scene was given (T = 1 /
  // rate is rounded), and a multiply keeps a division's latency out of the tick.
  const Axes<N> difference_m_per_s = (x_m - state->previous_x_m) * rate_hz;
  state->previous_x_m = x_m;

  Axes<N> v_m_per_s = difference_m_per_s;
  switch (config.kind) {
    case VelocityEstimatorKind::hapkit2019:
      v_m_per_s = 0.9 * difference_m_per_s + 0.1 * state->previous_difference_m_per_s;
      break;
    case VelocityEstimatorKind::hapkit2013: {
      // The sketch hard-coded T = 100 us; here T is the scene's period.
      constexpr double kPole = 0.95;
      v_m_per_s = 2.0 * kPole * state->v1_m_per_s - kPole * kPole * state->v2_m_per_s +
                  (1.0 - kPole) * (1.0 - kPole) * difference_m_per_s;
      break;
    }
    case VelocityEstimatorKind::difference:
      break;
    case VelocityEstimatorKind::lowpass:
      v_m_per_s = state->v1_m_per_s + config.lowpass_alpha * (difference_m_per_s - state->v1_m_per_s);
      break;
  }
  state->previous_difference_m_per_s = difference_m_per_s;
  state->v2_m_per_s = state->v1_m_per_s;
  state->v1_m_per_s = v_m_per_s;
  return v_m_per_s;
}

}  // namespace hapscene
