#pragma once
// A compiled scene: the immutable result of loading an environment file. Every run reads
// it through a const reference; everything a run changes lives in TickState.
#include <string>
#include <variant>
#include <vector>

#include "engine/core/effect_bank.hpp"
#include "engine/core/effect_input.hpp"
#include "engine/core/safety.hpp"
#include "engine/core/validate_thresholds.hpp"
#include "engine/core/velocity.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/devices/profile.hpp"
#include "engine/effects/damper.hpp"
#include "engine/effects/script_effect.hpp"
#include "engine/effects/spring.hpp"
#include "engine/effects/texture.hpp"
#include "engine/effects/wall.hpp"

namespace hapscene {

// One effect; the forces of all effects of a scene add up.
using Effect = std::variant<Spring, Wall, Damper, Texture, ScriptEffect>;

struct Scene {
  // What the tick reads, first and together: about four cache lines.
  double period_s{};                // 1 / rate_hz
  Needs needs;                      // union of the effects' needs: what step() computes
  Kinematics kinematics;            // the device's, compiled for the tick
  SafetyConfig safety;              // device limits lowered by the environment's
  VelocityEstimatorConfig velocity;
  EffectBank bank;                  // the built-in effects that can act, grouped for the tick

  double rate_hz{};                 // tick rate
  std::string name;
  std::string description;
  std::string source_path;          // the file it was loaded from, for messages

  DeviceProfile device;
  std::string device_file;          // the profile's file ("environments/devices/big.json"), or its shipped name

  std::vector<Effect> effects;      // as written in the file
  std::size_t script_count{};       // ScriptEffects among them (instance_index 0..n-1)

  ValidateThresholds validate;      // the optional "validate" block (the harness only)

  // Warnings found at load (printed to stderr by the loader; `validate` fails a check on
  // them): "environments/x.json: /effects/1 (wall): ... never acts ...".
  std::vector<std::string> load_warnings;
};

// Appends `effect` to the scene's list and, when it can act inside the workspace (safety
// must be set first), to its bank (or its script count) and needs.
void add_effect(Scene* scene, Effect effect);

}  // namespace hapscene
