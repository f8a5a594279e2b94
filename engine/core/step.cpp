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

void add_effect(Scene* scene, Effect effect) {
  scene->needs |= needs_of(effect);
  std::visit(
      [&](auto& e) {
        using Type = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<Type, ScriptEffect>) e.instance_index = scene->script_count++;
        else if constexpr (std::is_same_v<Type, Spring>) scene->bank.springs.push_back(e);
        else if constexpr (std::is_same_v<Type, Wall>) scene->bank.walls.push_back(e);
        else if constexpr (std::is_same_v<Type, Damper>) scene->bank.dampers.push_back(e);
        else if constexpr (std::is_same_v<Type, Texture>) scene->bank.textures.push_back(e);
        else static_assert(sizeof(Type) == 0, "a new effect type needs a group in EffectBank");
      },
      effect);
  scene->effects.push_back(std::move(effect));
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

namespace {

// Each script's force (one call per script per tick). Out of line, so that a tick of
// built-in effects only carries no call and needs no saved registers.
[[gnu::noinline]] double add_scripts_N(double force_N, const EffectInput& input, ScriptList& scripts,
                                       std::uint64_t* script_calls) noexcept {
  const ScriptInput script_input{input.x_m, input.v_m_per_s, input.t_s, input.dt_s};
  for (const auto& script : scripts) force_N += script->force_N(script_input);
  if (script_calls != nullptr) *script_calls += scripts.size();
  return force_N;
}

// The effects stage: the built-in bank, then the scripts.
[[gnu::always_inline]] inline double add_effects_N(const Scene& scene, const EffectInput& input,
                                                   ScriptList& scripts,
                                                   std::uint64_t* script_calls) noexcept {
  double force_N = scene.bank.force_N(input);
  if (!scripts.empty()) force_N = add_scripts_N(force_N, input, scripts, script_calls);
  return force_N;
}

// One tick. The common case (no cross-fade) is its own instantiation, so a plain tick
// carries no cross-fade branches and keeps its values in registers.
template <bool kFading>
[[gnu::always_inline]] inline void step_tick(const Scene& scene, std::int32_t raw_counts,
                                             TickState* state, const Crossfade* fade) noexcept {
  // Sensor: unwrap the MR sensor and convert counts to handle position. (The tick count
  // converts as signed: one instruction, and runs never reach 2^63 ticks.)
  state->t_s = static_cast<double>(static_cast<std::int64_t>(state->tick)) * scene.period_s;
  state->raw_counts = raw_counts;
  state->unwrapped_counts = state->flip_counter.update(raw_counts);
  state->x_m = counts_to_position_m(scene.kinematics, state->unwrapped_counts);

  // Velocity: only when some effect reads it (of either scene during a cross-fade).
  Needs needs = scene.needs;
  if constexpr (kFading) needs |= fade->from->needs;
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
  double effects_N = add_effects_N(scene, input, state->scripts, &state->script_calls);
  if constexpr (kFading) {
    const double from_N = add_effects_N(*fade->from, input, *fade->from_scripts, &state->script_calls);
    effects_N = (1.0 - fade->weight_to) * from_N + fade->weight_to * effects_N;
  }
  state->effects_force_N = effects_N;

  // Safety, then the motor command the board needs.
  state->output_N = apply_safety(scene.safety, state->x_m, effects_N, &state->safety);
  state->command = force_to_motor(scene.kinematics, state->output_N);
  ++state->tick;
}

}  // namespace

double sum_effects_N(const Scene& scene, const EffectInput& input, ScriptList& scripts,
                     std::uint64_t* script_calls) noexcept {
  return add_effects_N(scene, input, scripts, script_calls);
}

void collect_script_garbage(TickState* state) noexcept {
  for (const auto& script : state->scripts) script->collect_garbage();
}

void step(const Scene& scene, std::int32_t raw_counts, TickState* state,
          const Crossfade* fade) noexcept {
  if (fade == nullptr) [[likely]] {
    step_tick<false>(scene, raw_counts, state, nullptr);
  } else {
    step_tick<true>(scene, raw_counts, state, fade);
  }
}

}  // namespace hapscene
