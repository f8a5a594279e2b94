#pragma once
// One tick of the haptic loop: read device -> sensor pipeline -> effects -> safety ->
// motor command. No allocation, no exception, no lock, no I/O.
#include <cstdint>

#include "engine/effects/effect_input.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

// A cross-fade from a scene being replaced (hot reload): the effects stage gives
// (1 - weight_to) * F_from + weight_to * F_to, so the handle never gets a jolt.
template <int N>
struct CrossfadeOf {
  const SceneOf<N>* from{};
  ScriptList* from_scripts{};
  typename SceneParts<N>::Effects::Bank::RunState* from_runs{};
  double weight_to{};  // in [0, 1]
};

using Crossfade = CrossfadeOf<1>;

// A full tick from the device's raw reading. Writes state->command (and every stage's
// field). With `fade`, `scene` is the new scene and state->scripts its instances.
// Compiled once per axis count (step.cpp).
template <int N>
void step(const SceneOf<N>& scene, const typename SceneParts<N>::Reading& reading,
          TickStateOf<N>* state, const CrossfadeOf<N>* fade = nullptr) noexcept;

// The effects stage open loop (without history): the sum of the compiled effects' forces
// (the bank's, each shape's proxy at the nearest point of its boundary, then each
// script's) for one input, with the given script instances. For fields (every 1-D effect)
// it is what the tick computes.
template <int N>
Axes<N> sum_effects_N(const SceneOf<N>& scene, const EffectInputOf<N>& input,
                      ScriptList& scripts) noexcept;

// Housekeeping for the tick's slack, after the command is written: a little garbage
// collection for each script (their collectors are stopped while they compute force).
template <int N>
void collect_script_garbage(TickStateOf<N>* state) noexcept {
  for (const auto& script : state->scripts) script->collect_garbage();
}

}  // namespace hapscene
