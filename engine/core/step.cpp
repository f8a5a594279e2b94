#include "engine/core/step.hpp"

#include "engine/devices/kinematics.hpp"

namespace hapscene {

Needs needs_of(const Effect& effect) noexcept {
  return std::visit(
      [](const auto& e) {
        if constexpr (std::is_same_v<std::decay_t<decltype(e)>, ScriptEffect>) return e.needs;
        else return std::decay_t<decltype(e)>::kNeeds;
      },
      effect);
}

ScriptList make_script_instances(const Scene& scene) {
  // One sandboxed instance per script effect, in scene order (ScriptEffect::instance_index).
  ScriptList scripts;
  scripts.reserve(scene.script_count);
  for (const Effect& effect : scene.effects) {
    if (const auto* script = std::get_if<ScriptEffect>(&effect)) {
      scripts.push_back(ScriptInstance::create(*script->program));
      scripts.back()->reset();
    }
  }
  return scripts;
}

TickState make_tick_state(const Scene& scene) {
  TickState state;
  state.flip_counter.threshold_counts = scene.device.sensor.flip_threshold_counts;
  state.flip_counter.span_counts = scene.device.sensor.span_counts;
  state.scripts = make_script_instances(scene);
  return state;
}

double sum_effects_N(const Scene& scene, const EffectInput& input, ScriptList& scripts,
                     std::uint64_t* script_calls) noexcept {
  double force_N = 0.0;
  for (const Effect& effect : scene.effects) {
    force_N += std::visit(
        [&](const auto& e) noexcept {
          if constexpr (std::is_same_v<std::decay_t<decltype(e)>, ScriptEffect>) {
            const ScriptInput script_input{input.x_m, input.v_m_per_s, input.t_s, input.dt_s};
            if (script_calls != nullptr) ++*script_calls;
            return scripts[e.instance_index]->force_N(script_input);
          } else {
            return e.force_N(input);
          }
        },
        effect);
  }
  return force_N;
}

void collect_script_garbage(TickState* state) noexcept {
  for (const auto& script : state->scripts) script->collect_garbage();
}

void step(const Scene& scene, std::int32_t raw_counts, TickState* state,
          const Crossfade* fade) noexcept {
  // Sensor: unwrap the MR sensor and convert counts to handle position.
  state->t_s = static_cast<double>(state->tick) * scene.period_s;
  state->raw_counts = raw_counts;
  state->unwrapped_counts = state->flip_counter.update(raw_counts);
  state->x_m = counts_to_position_m(scene.kinematics, state->unwrapped_counts);

  // Velocity: only when some effect reads it (of either scene during a cross-fade).
  const Needs needs = fade == nullptr ? scene.needs : Needs(scene.needs) |= fade->from->needs;
  if (needs.velocity) {
    state->v_m_per_s =
        estimate_velocity(scene.velocity, scene.period_s, state->x_m, &state->velocity_state);
  }

  // Effects: the sum of every effect's force.
  EffectInput input;
  input.x_m = state->x_m;
  input.v_m_per_s = state->v_m_per_s;
  input.t_s = needs.time ? state->t_s : 0.0;
  input.dt_s = scene.period_s;
  state->effects_force_N = sum_effects_N(scene, input, state->scripts, &state->script_calls);
  if (fade != nullptr) {
    const double from_N = sum_effects_N(*fade->from, input, *fade->from_scripts, &state->script_calls);
    state->effects_force_N = (1.0 - fade->weight_to) * from_N + fade->weight_to * state->effects_force_N;
  }

  // Safety, then the motor command the board needs.
  state->output_N = apply_safety(scene.safety, state->x_m, state->effects_force_N, &state->safety);
  state->command = force_to_motor(scene.kinematics, state->output_N);
  ++state->tick;
}

}  // namespace hapscene
