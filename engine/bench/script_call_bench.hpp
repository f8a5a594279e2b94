#pragma once
// Timing loops of a script's force(s) call alone: no sensor stage, kinematics, safety or
// motor command, so a 1-D and a 2-D script can be compared by what the script costs (a
// whole 2-D tick also pays for the linkage's kinematics, which a built-in 2-D effect
// pays too). And the same scenes with every script run by the Lua VM alone, to show
// what the translation of a straight-line force (engine/lua/force_program.hpp) saves.
#include <memory>
#include <vector>

#include "engine/bench/tick_bench.hpp"
#include "engine/lua/script.hpp"

namespace hapscene {

// force_N of a fresh, reset instance of `program` (compiled for N axes), on inputs[i] for
// each reading i (the readings are indices into `inputs`).
template <int N>
std::unique_ptr<TickLoop> script_call_tick_loop(const ScriptProgram& program, std::vector<ScriptInputOf<N>> inputs);

// `count` inputs with the handle swinging over +-20 mm (round (x0, y0) in 2-D) at 1 kHz.
std::vector<ScriptInput> swinging_script_inputs(std::size_t count);
std::vector<PlanarScriptInput> swinging_planar_script_inputs(std::size_t count, double x0_m, double y0_m);

// The first script effect's program of a scene (null when it has none).
template <typename Scene>
const ScriptProgram* first_script_program(const Scene& scene) {
  for (const auto& effect : scene.effects) {
    if (const auto* script = std::get_if<ScriptEffect>(&effect)) return script->program.get();
  }
  return nullptr;
}

// `scene` with each script's force run by the Lua VM alone (ScriptLimits::translate_force off).
template <typename Scene>
Scene with_scripts_in_vm(Scene scene) {
  for (auto& effect : scene.effects) {
    if (auto* script = std::get_if<ScriptEffect>(&effect)) {
      auto program = std::make_shared<ScriptProgram>(*script->program);
      program->limits.translate_force = false;
      script->program = std::move(program);
    }
  }
  return scene;
}

}  // namespace hapscene
