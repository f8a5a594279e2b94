#include "engine/scene/safety.hpp"

namespace hapscene {

void finalise_safety(double period_s, SafetyConfig* config) noexcept {
  config->max_step_N = config->slew_limit_N_per_s * period_s;
  config->ramp_step_per_tick = config->soft_start_s > 0.0 ? period_s / config->soft_start_s : 1.0;
}

double apply_ramp(const SafetyConfig& config, double output_N, SafetyState* state) noexcept {
  if (state->position_hold != PositionHold::none) {
    ++state->counters.position_hold_ticks;
    if (state->position_hold == PositionHold::cut || !state->started) {
      state->started = false;
      state->ramp_gain = 0.0;
      return 0.0;
    }
    state->ramp_gain = std::max(0.0, state->ramp_gain - config.ramp_step_per_tick);
    return output_N * state->ramp_gain;
  }
  if (!state->started) {
    state->started = true;
    state->ramp_gain = std::abs(output_N) > config.soft_start_threshold_N ? 0.0 : 1.0;
  }
  if (state->ramp_gain < 1.0) {
    output_N *= state->ramp_gain;
    state->ramp_gain = std::min(1.0, state->ramp_gain + config.ramp_step_per_tick);
    ++state->counters.soft_start_ticks;
  }
  return output_N;
}

void restart_soft_start(SafetyState* state) noexcept {
  state->started = false;
  state->ramp_gain = 0.0;
}

}  // namespace hapscene
