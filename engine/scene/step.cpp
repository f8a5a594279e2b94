#include "engine/scene/step.hpp"

#include <type_traits>

#include "engine/devices/device_model.hpp"

namespace hapscene {

template <int N>
void add_effect(SceneOf<N>* scene, typename SceneParts<N>::Effects::Variant effect) {
  const Axes<N> min_m = scene->safety.workspace_min_m;
  const Axes<N> max_m = scene->safety.workspace_max_m;
  // A built-in effect that cannot act inside the workspace (zero gain, or a wall whose
  // solid side lies beyond it) is listed but not compiled: it costs the tick nothing and
  // adds no needs.
  std::visit(
      [&](auto& e) {
        using Type = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<Type, ScriptEffect>) {
          e.instance_index = scene->script_count++;
          scene->needs |= e.needs;
        } else {
          if (!e.can_act_within(min_m, max_m)) return;
          scene->bank.append(e);
          scene->needs |= Type::kNeeds;
        }
      },
      effect);
  scene->effects.push_back(std::move(effect));
}

template <int N>
ScriptList make_script_instances(const SceneOf<N>& scene) {
  // One sandboxed instance per script effect, in scene order (ScriptEffect::instance_index).
  ScriptList scripts;
  scripts.reserve(scene.script_count);
  for (const auto& effect : scene.effects) {
    if (const auto* script = std::get_if<ScriptEffect>(&effect)) {
      scripts.push_back(ScriptInstance::create(*script->program));
      scripts.back()->reset();
    }
  }
  return scripts;
}

template <int N>
TickStateOf<N> make_tick_state(const SceneOf<N>& scene) {
  TickStateOf<N> state;
  state.sensor = make_sensor_state(scene.device_model);
  state.scripts = make_script_instances(scene);
  state.effect_runs = scene.bank.make_run_state();
  return state;
}

namespace {

// Each script's force (one call per script per tick): N numbers in a scene of N axes.
template <int N>
Axes<N> add_scripts_N(Axes<N> force_N, const EffectInputOf<N>& input, ScriptList& scripts,
                      std::uint64_t* script_calls) noexcept {
  const ScriptInputOf<N> script_input{input.x_m, input.v_m_per_s, input.t_s, input.dt_s};
  for (const auto& script : scripts) force_N += script->force_N(script_input);
  if (script_calls != nullptr) *script_calls += scripts.size();
  return force_N;
}

// A pose the device model does not trust holds the force like an untrusted position
// (PositionHold): near a singularity it ramps out, at an impossible pose it is cut.
void hold_for_pose(PoseTrust trust, SafetyCounters* counters, PositionHold* hold) noexcept {
  ++counters->pose_hold_ticks;
  const PositionHold pose_hold = trust == PoseTrust::invalid ? PositionHold::cut : PositionHold::ramp_out;
  if (pose_hold > *hold) *hold = pose_hold;
}

// The effects stage: the built-in bank, then the scripts (when kScripts).
template <bool kScripts, int N>
[[gnu::always_inline]] inline Axes<N> add_effects_N(const SceneOf<N>& scene,
                                                    const EffectInputOf<N>& input,
                                                    ScriptList& scripts,
                                                    typename SceneParts<N>::Effects::Bank::RunState& runs,
                                                    std::uint64_t* script_calls) noexcept {
  Axes<N> force_N = scene.bank.force_N(input, runs);
  if constexpr (kScripts) force_N = add_scripts_N(force_N, input, scripts, script_calls);
  return force_N;
}

// The scene's device model's tick stages and the variants step() compiles ahead
// (TickStages, engine/devices/device.hpp).
template <int N>
using TickStagesOf = TickStages<typename SceneParts<N>::DeviceModel>;
template <int N>
using TickVariantOf = typename TickStagesOf<N>::Variant;

// One tick of a scene with N axes, written once for every N. Each case is its own
// instantiation (step_tick, out of line, reached from step() by a tail call): scripts,
// cross-fades, built-in effects alone; a tick of built-in effects alone is also compiled
// for each variant the device model compiles ahead (kVariant: a planar family, its
// sensor, linkage and drive branches decided). The device model's two stages (sense,
// command) are its model's and inlined. Where the model has a steady tick (kSteady, see
// steady_tick: the 1-DOF capstan's), the common tick of built-in effects in the steady
// state is inlined into step() itself: it makes no call at all (the flip counter's and
// the soft start's rare paths are known not to run), so it saves no registers and keeps
// its values in them.
template <int N, bool kFading, bool kScripts, TickVariantOf<N> kVariant = TickStagesOf<N>::kGeneral, bool kSteady = false>
[[gnu::always_inline]] inline void tick_body(const SceneOf<N>& scene,
                                             const typename SceneParts<N>::Reading& reading,
                                             TickStateOf<N>* state, const CrossfadeOf<N>* fade) noexcept {
  // Sensor: the device model turns the reading into the handle position. (The tick count
  // converts as signed: one instruction, and runs never reach 2^63 ticks.)
  state->t_s = static_cast<double>(static_cast<std::int64_t>(state->tick)) * scene.period_s;
  state->x_m = TickStagesOf<N>::template sense<kVariant>(scene.device_model, reading, &state->sensor);
  const PoseTrust trust = pose_trust(scene.device_model, state->sensor);
  if (trust != PoseTrust::trusted) [[unlikely]] {
    hold_for_pose(trust, &state->safety.counters, &state->safety.position_hold);
  }

  // Velocity: only when some effect reads it (of either scene during a cross-fade).
  Needs needs = scene.needs;
  if constexpr (kFading) needs |= fade->from->needs;
  if (needs.velocity) {
    state->v_m_per_s =
        estimate_velocity(scene.velocity, scene.rate_hz, state->x_m, &state->velocity_state);
  }

  // Effects: the sum of every effect's force.
  EffectInputOf<N> input;
  input.x_m = state->x_m;
  input.v_m_per_s = state->v_m_per_s;
  input.t_s = state->t_s;
  input.dt_s = scene.period_s;
  Axes<N> effects_N =
      add_effects_N<kScripts>(scene, input, state->scripts, state->effect_runs, &state->script_calls);
  if constexpr (kFading) {
    const Axes<N> from_N = add_effects_N<kScripts>(*fade->from, input, *fade->from_scripts,
                                                   *fade->from_runs, &state->script_calls);
    effects_N = (1.0 - fade->weight_to) * from_N + fade->weight_to * effects_N;
  }
  state->effects_force_N = effects_N;

  // Safety, then the motor command the board needs.
  state->output_N = apply_safety<N, !kSteady>(scene.safety, state->x_m, effects_N, &state->safety);
  TickStagesOf<N>::template command<kVariant>(scene.device_model, state->sensor, state->output_N, &state->command);
  if (command_saturated(state->command)) ++state->safety.counters.motor_saturated_ticks;
  ++state->tick;
}

template <int N, bool kFading, bool kScripts, TickVariantOf<N> kVariant = TickStagesOf<N>::kGeneral>
[[gnu::noinline]] void step_tick(const SceneOf<N>& scene, const typename SceneParts<N>::Reading& reading,
                                 TickStateOf<N>* state, const CrossfadeOf<N>* fade) noexcept {
  tick_body<N, kFading, kScripts, kVariant>(scene, reading, state, fade);
}

// A tick in its steady state: the device model calls the reading steady (the capstan's:
// it cannot be a flip of the sensor, within the threshold of the flip counter's full
// window), and neither the soft start nor a held position acts. Such a tick calls nothing
// (those are the rare paths that do).
template <int N>
bool steady_tick(const typename SceneParts<N>::SensorState& sensor, typename SceneParts<N>::Reading reading,
                 const SafetyStateOf<N>& safety) noexcept {
  return TickStagesOf<N>::steady_reading(sensor, reading) && !ramp_acts(safety);
}

}  // namespace

template <int N>
Axes<N> sum_effects_N(const SceneOf<N>& scene, const EffectInputOf<N>& input,
                      ScriptList& scripts) noexcept {
  // Open loop: the built-in effects without history (a shape's proxy at the nearest point
  // of its boundary), then the scripts.
  return add_scripts_N(scene.bank.open_loop_force_N(input), input, scripts, nullptr);
}

template <int N>
void step(const SceneOf<N>& scene, const typename SceneParts<N>::Reading& reading,
          TickStateOf<N>* state, const CrossfadeOf<N>* fade) noexcept {
  if (fade != nullptr) [[unlikely]] {
    step_tick<N, true, true>(scene, reading, state, fade);
  } else if (state->scripts.empty()) [[likely]] {
    // The variant compiled for the scene's device family, when its model has one (one
    // branch, always the same).
    if constexpr (TickStagesOf<N>::kVariantsAhead) {
      if (TickStagesOf<N>::dispatch(scene.device_model, [&]<TickVariantOf<N> kVariant>() {
            step_tick<N, false, false, kVariant>(scene, reading, state, nullptr);
          })) {
        return;
      }
    }
    if constexpr (TickStagesOf<N>::kSteadyTick) {
      // The steady tick in line here: the common tick of built-in effects makes no call
      // at all, so it saves no registers (the others are tail calls).
      if (steady_tick<N>(state->sensor, reading, state->safety)) [[likely]] {
        tick_body<N, false, false, TickStagesOf<N>::kGeneral, true>(scene, reading, state, nullptr);
        return;
      }
    }
    step_tick<N, false, false>(scene, reading, state, nullptr);
  } else {
    step_tick<N, false, true>(scene, reading, state, nullptr);
  }
}

// The axis counts scenes are compiled for.
#define HAPSCENE_SCENE_FUNCTIONS(N)                                                           \
  template void add_effect<N>(SceneOf<N>*, SceneParts<N>::Effects::Variant);                   \
  template ScriptList make_script_instances<N>(const SceneOf<N>&);                             \
  template TickStateOf<N> make_tick_state<N>(const SceneOf<N>&);                               \
  template Axes<N> sum_effects_N<N>(const SceneOf<N>&, const EffectInputOf<N>&, ScriptList&) noexcept; \
  template void step<N>(const SceneOf<N>&, const SceneParts<N>::Reading&, TickStateOf<N>*,     \
                        const CrossfadeOf<N>*) noexcept;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_SCENE_FUNCTIONS)
#undef HAPSCENE_SCENE_FUNCTIONS

}  // namespace hapscene
