#include "engine/core/safety.hpp"

#include <algorithm>
#include <cmath>

namespace hapscene {

void finalise_safety(double period_s, SafetyConfig* config) noexcept {
  config->max_step_N = config->slew_limit_N_per_s * period_s;
  config->ramp_step_per_tick = config->soft_start_s > 0.0 ? period_s / config->soft_start_s : 1.0;
}

double apply_safety(const SafetyConfig& config, double x_m, double force_N,
                    SafetyState* state) noexcept {
  double output_N = apply_static_safety(config, x_m, force_N, &state->counters);

  // 3. Soft start: decided on the first tick from the force the scene asks for there.
  if (!state->started) {
    state->started = true;
    state->ramp_gain = std::abs(output_N) > config.soft_start_threshold_N ? 0.0 : 1.0;
  }
  if (state->ramp_gain < 1.0) {
    output_N *= state->ramp_gain;
    state->ramp_gain = std::min(1.0, state->ramp_gain + config.ramp_step_per_tick);
    ++state->counters.soft_start_ticks;
  }

  // 5. Slew limit against the previous output.
  const double step_N = output_N - state->previous_output_N;
  if (std::abs(step_N) > config.max_step_N) {
    output_N = state->previous_output_N + std::copysign(config.max_step_N, step_N);
    ++state->counters.slew_limited_ticks;
  }
  state->previous_output_N = output_N;
  return output_N;
}

void restart_soft_start(SafetyState* state) noexcept { state->started = false; }

}  // namespace hapscene
