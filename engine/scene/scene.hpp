#pragma once
// A compiled scene: the immutable result of loading an environment file. Every run reads
// it through a const reference; everything a run changes lives in TickState.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "engine/devices/device.hpp"
#include "engine/devices/device_model.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/devices/planar/planar_tick.hpp"
#include "engine/devices/profile.hpp"
#include "engine/effects/effect_types.hpp"
#include "engine/effects/planar/planar_effect_types.hpp"
#include "engine/scene/safety.hpp"
#include "engine/scene/velocity.hpp"

namespace hapscene {

// What a scene with N axes is made of: its device's profile and compiled model, what the
// device reads and takes each tick, and its effect types. One specialisation per N
// (docs/explanation/n-axis.md); everything else of a scene, its tick and its run is written once.
template <int N>
struct SceneParts;

template <>
struct SceneParts<1> {
  using Profile = DeviceProfile;
  using DeviceModel = hapscene::DeviceModel;
  using SensorState = hapscene::SensorState;
  using Reading = DeviceIo<1>::Reading;  // the sensor's raw count
  using Command = DeviceIo<1>::Command;  // the motor driver's duty and direction
  using Effects = BuiltInEffects;
  static constexpr const char* kKindName = "1-DOF";  // in messages
};

// Two axes: a planar linkage (the Haplink, pantographs), the 2-D effects.
template <>
struct SceneParts<2> {
  using Profile = PlanarProfile;
  using DeviceModel = PlanarTickModel;
  using SensorState = PlanarTickSensor;
  using Reading = DeviceIo<2>::Reading;  // each joint's counts or angle
  using Command = DeviceIo<2>::Command;  // each motor's command
  using Effects = PlanarBuiltInEffects;
  static constexpr const char* kKindName = "2-DOF (planar)";
};

template <int N>
struct SceneOf {
  using Parts = SceneParts<N>;
  static constexpr int kAxes = N;

  // What the tick reads, first and together: about four cache lines.
  double period_s{};                // 1 / rate_hz
  Needs needs;                      // union of the effects' needs: what step() computes
  typename Parts::DeviceModel device_model;  // the device's sensor and drive, compiled for the tick
  SafetyConfigOf<N> safety;         // device limits lowered by the environment's
  VelocityEstimatorConfig velocity;
  typename Parts::Effects::Bank bank;  // the built-in effects that can act, grouped for the tick

  double rate_hz{};                 // tick rate
  std::string name;
  std::string source_path;          // the file it was loaded from, for messages

  typename Parts::Profile device;
  std::string device_file;          // the profile's file ("environments/devices/big.json"), or its shipped name

  std::vector<typename Parts::Effects::Variant> effects;  // as written in the file
  std::size_t script_count{};       // ScriptEffects among them (instance_index 0..n-1)

  // Warnings found at load (printed to stderr by the loader; `validate` fails a check on
  // them): "environments/x.json: /effects/1 (wall): ... never acts ...".
  std::vector<std::string> load_warnings;
};

// A 1-DOF scene (the Hapkit's), and a planar one.
using Scene = SceneOf<1>;
using PlanarScene = SceneOf<2>;

// Appends `effect` to the scene's list and, when it can act inside the workspace (safety
// must be set first), to its bank (or its script count) and needs.
// (Compiled for the axis counts of step.cpp.)
template <int N>
void add_effect(SceneOf<N>* scene, typename SceneParts<N>::Effects::Variant effect);

}  // namespace hapscene
