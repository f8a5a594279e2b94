#pragma once
// One tick of the haptic loop: read device -> sensor pipeline -> effects -> safety ->
// motor command. No allocation, no exception, no lock, no I/O.
#include <cstdint>

#include "engine/core/effect_input.hpp"
#include "engine/core/scene.hpp"
#include "engine/core/tick_state.hpp"

namespace hapscene {

// A full tick from a raw sensor reading. Writes state->command (and every stage's field).
void step(const Scene& scene, std::int32_t raw_counts, TickState* state) noexcept;

// The effects stage alone: the sum of every effect's force for one input.
double sum_effects_N(const Scene& scene, const EffectInput& input, TickState* state) noexcept;

}  // namespace hapscene
