#include "engine/core/step.hpp"

#include "engine/devices/kinematics.hpp"

namespace hapscene {

Needs needs_of(const Effect& effect) noexcept {
  return std::visit([](const auto& e) { return std::decay_t<decltype(e)>::kNeeds; }, effect);
}

TickState make_tick_state(const Scene& scene) {
  TickState state;
  state.flip_counter.threshold_counts = scene.device.sensor.flip_threshold_counts;
  state.flip_counter.span_counts = scene.device.sensor.span_counts;
  return state;
}

double sum_effects_N(const Scene& scene, const EffectInput& input, TickState* /*state*/) noexcept {
  double force_N = 0.0;
  for (const Effect& effect : scene.effects) {
    force_N += std::visit([&input](const auto& e) noexcept { return e.force_N(input); }, effect);
  }
  return force_N;
}

void step(const Scene& scene, std::int32_t raw_counts, TickState* state) noexcept {
  // Sensor: unwrap the MR sensor and convert counts to handle position.
  state->t_s = static_cast<double>(state->tick) * scene.period_s;
  state->raw_counts = raw_counts;
  state->unwrapped_counts = state->flip_counter.update(raw_counts);
  state->x_m = counts_to_position_m(scene.kinematics, state->unwrapped_counts);

  // Velocity: only when some effect reads it.
  if (scene.needs.velocity) {
    state->v_m_per_s =
        estimate_velocity(scene.velocity, scene.period_s, state->x_m, &state->velocity_state);
  }

  // Effects: the sum of every effect's force.
  EffectInput input;
  input.x_m = state->x_m;
  input.v_m_per_s = state->v_m_per_s;
  input.t_s = scene.needs.time ? state->t_s : 0.0;
  input.dt_s = scene.period_s;
  state->effects_force_N = sum_effects_N(scene, input, state);

  // Safety, then the motor command the board needs.
  state->output_N = apply_safety(scene.safety, state->x_m, state->effects_force_N, &state->safety);
  state->command = force_to_motor(scene.kinematics, state->output_N);
  ++state->tick;
}

}  // namespace hapscene
