#pragma once
// Everything one run of a scene changes, grouped by the pipeline stage that writes it.
// A new TickState is a fresh run: the same scene can be run twice without surprises.
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/devices/device_model.hpp"
#include "engine/lua/script.hpp"
#include "engine/scene/safety.hpp"
#include "engine/scene/velocity.hpp"

namespace hapscene {

struct Scene;

// The script instances of one run of a scene, one per ScriptEffect in scene order.
using ScriptList = std::vector<std::unique_ptr<ScriptInstance>>;

struct TickState {
  // Clock.
  std::uint64_t tick{};           // ticks completed
  double t_s{};                   // time of the current tick since the run started

  // Sensor stage: the device's reading -> handle position (the device model's own state).
  SensorState sensor;
  double x_m{};

  // Velocity stage (only when the scene needs it).
  VelocityState velocity_state;
  double v_m_per_s{};

  // Effects stage.
  ScriptList scripts;             // the current scene's script instances, made at start
  double effects_force_N{};       // sum of all effects: what the scene asks for
  std::uint64_t script_calls{};           // calls into script effects (one per script per tick)

  // Safety stage.
  SafetyState safety;
  double output_N{};              // what the device is commanded

  // Command stage.
  MotorCommand command;
};

// A fresh state for a run of `scene`: new script instances, each reset. Throws InputError
// when a script instance cannot be created.
TickState make_tick_state(const Scene& scene);

// New, reset script instances for `scene` (what make_tick_state puts in `scripts`).
ScriptList make_script_instances(const Scene& scene);

}  // namespace hapscene
