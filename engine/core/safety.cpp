#include "engine/core/safety.hpp"

namespace hapscene {

void finalise_safety(double period_s, SafetyConfig* config) noexcept {
  config->max_step_N = config->slew_limit_N_per_s * period_s;
  config->ramp_step_per_tick = config->soft_start_s > 0.0 ? period_s / config->soft_start_s : 1.0;
}

void restart_soft_start(SafetyState* state) noexcept {
  state->started = false;
  state->ramp_gain = 0.0;
}

}  // namespace hapscene
