#pragma once
// Everything one run of a scene changes, grouped by the pipeline stage that writes it.
// A new TickState is a fresh run: the same scene can be run twice without surprises.
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/lua/script.hpp"
#include "engine/scene/safety.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/velocity.hpp"

namespace hapscene {

// The script instances of one run of a scene, one per ScriptEffect in scene order.
using ScriptList = std::vector<std::unique_ptr<ScriptInstance>>;

// The state of one run of a scene with N axes (handle values are Axes<N>).
template <int N>
struct TickStateOf {
  // Clock.
  std::uint64_t tick{};           // ticks completed
  double t_s{};                   // time of the current tick since the run started

  // Sensor stage: the device's reading -> handle position (the device model's own state).
  typename SceneParts<N>::SensorState sensor;
  Axes<N> x_m{};

  // Velocity stage (only when the scene needs it).
  VelocityStateOf<N> velocity_state;
  Axes<N> v_m_per_s{};

  // Effects stage.
  ScriptList scripts;             // the current scene's script instances, made at start
  typename SceneParts<N>::Effects::Bank::RunState effect_runs;  // built-in effects' run state (proxies)
  Axes<N> effects_force_N{};      // sum of all effects: what the scene asks for
  std::uint64_t script_calls{};           // calls into script effects (one per script per tick)

  // Safety stage.
  SafetyStateOf<N> safety;
  Axes<N> output_N{};             // what the device is commanded

  // Command stage.
  typename SceneParts<N>::Command command;
};

using TickState = TickStateOf<1>;

// A fresh state for a run of `scene`: new script instances, each reset. Throws InputError
// when a script instance cannot be created.
template <int N>
TickStateOf<N> make_tick_state(const SceneOf<N>& scene);

// New, reset script instances for `scene` (what make_tick_state puts in `scripts`).
template <int N>
ScriptList make_script_instances(const SceneOf<N>& scene);

}  // namespace hapscene
