#pragma once
// What a 2-D effect sees each tick: the handle state in the device's task frame (SI,
// x and y in metres). The same fields as the 1-D EffectInput, with vectors for position
// and velocity; effects declare what they read besides position with Needs.
#include "engine/base/axes.hpp"
#include "engine/effects/effect_input.hpp"

namespace hapscene {

using PlanarInput = EffectInputOf<2>;

}  // namespace hapscene
