#pragma once
// A compiled scene: the immutable result of loading an environment file. Every run reads
// it through a const reference; everything a run changes lives in TickState.
#include <string>
#include <variant>
#include <vector>

#include "engine/devices/device_model.hpp"
#include "engine/devices/profile.hpp"
#include "engine/effects/effect_types.hpp"
#include "engine/scene/safety.hpp"
#include "engine/scene/velocity.hpp"

namespace hapscene {

struct Scene {
  // What the tick reads, first and together: about four cache lines.
  double period_s{};                // 1 / rate_hz
  Needs needs;                      // union of the effects' needs: what step() computes
  DeviceModel device_model;         // the device's sensor and drive, compiled for the tick
  SafetyConfig safety;              // device limits lowered by the environment's
  VelocityEstimatorConfig velocity;
  EffectBank bank;                  // the built-in effects that can act, grouped for the tick

  double rate_hz{};                 // tick rate
  std::string name;
  std::string source_path;          // the file it was loaded from, for messages

  DeviceProfile device;
  std::string device_file;          // the profile's file ("environments/devices/big.json"), or its shipped name

  std::vector<Effect> effects;      // as written in the file
  std::size_t script_count{};       // ScriptEffects among them (instance_index 0..n-1)

  // Warnings found at load (printed to stderr by the loader; `validate` fails a check on
  // them): "environments/x.json: /effects/1 (wall): ... never acts ...".
  std::vector<std::string> load_warnings;
};

// Appends `effect` to the scene's list and, when it can act inside the workspace (safety
// must be set first), to its bank (or its script count) and needs.
void add_effect(Scene* scene, Effect effect);

}  // namespace hapscene
