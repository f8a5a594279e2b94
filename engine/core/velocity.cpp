#include "engine/core/velocity.hpp"

#include <cmath>
#include <numbers>

namespace hapscene {

double lowpass_alpha_for(double cutoff_Hz, double period_s) noexcept {
  return 1.0 - std::exp(-2.0 * std::numbers::pi * cutoff_Hz * period_s);
}

double estimate_velocity(const VelocityEstimatorConfig& config, double period_s, double x_m,
                         VelocityState* state) noexcept {
  if (!state->started) {
    state->started = true;
    state->previous_x_m = x_m;
    return 0.0;
  }
  const double difference_m_per_s = (x_m - state->previous_x_m) / period_s;
  state->previous_x_m = x_m;

  double v_m_per_s = difference_m_per_s;
  switch (config.kind) {
    case VelocityEstimatorKind::hapkit2019:
      v_m_per_s = 0.9 * difference_m_per_s + 0.1 * state->v1_m_per_s;
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
  state->v2_m_per_s = state->v1_m_per_s;
  state->v1_m_per_s = v_m_per_s;
  return v_m_per_s;
}

}  // namespace hapscene
