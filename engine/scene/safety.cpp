#include "engine/scene/safety.hpp"

namespace hapscene {

template <int N>
Axes<N> apply_ramp(const SafetyConfigOf<N>& config, Axes<N> output_N, SafetyStateOf<N>* state) noexcept {
  if (state->position_hold != PositionHold::none) {
    ++state->counters.position_hold_ticks;
    if (state->position_hold == PositionHold::cut || !state->started) {
      state->started = false;
      state->ramp_gain = 0.0;
      return Axes<N>{};
    }
    state->ramp_gain = std::max(0.0, state->ramp_gain - config.ramp_step_per_tick);
    return output_N * state->ramp_gain;
  }
  if (!state->started) {
    state->started = true;
    state->ramp_gain = norm(output_N) > config.soft_start_threshold_N ? 0.0 : 1.0;
  }
  if (state->ramp_gain < 1.0) {
    output_N *= state->ramp_gain;
    state->ramp_gain = std::min(1.0, state->ramp_gain + config.ramp_step_per_tick);
    ++state->counters.soft_start_ticks;
  }
  return output_N;
}

bool inside_polygon(const std::vector<Vec2>& polygon_m, const Vec2& p_m) noexcept {
  bool inside = false;
  const std::size_t n = polygon_m.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = polygon_m[i];
    const Vec2& b = polygon_m[j];
    if ((a[1] > p_m[1]) != (b[1] > p_m[1]) &&
        p_m[0] < (b[0] - a[0]) * (p_m[1] - a[1]) / (b[1] - a[1]) + a[0]) {
      inside = !inside;
    }
  }
  return inside;
}

// The scenes' axis counts.
#define HAPSCENE_APPLY_RAMP(N) \
  template Axes<N> apply_ramp<N>(const SafetyConfigOf<N>&, Axes<N>, SafetyStateOf<N>*) noexcept;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_APPLY_RAMP)
#undef HAPSCENE_APPLY_RAMP

}  // namespace hapscene
