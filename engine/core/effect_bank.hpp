#pragma once
// A scene's built-in effects grouped by type, compiled once at load: the tick loops over
// each group as a plain array, with no per-effect dispatch, so a scene pays only for the
// groups it has (an empty group costs a comparison). Within a group effects keep their
// order in the file; the groups add up springs, walls, dampers, textures, then scripts.
#include <vector>

#include "engine/core/effect_input.hpp"
#include "engine/effects/damper.hpp"
#include "engine/effects/spring.hpp"
#include "engine/effects/texture.hpp"
#include "engine/effects/wall.hpp"

namespace hapscene {

struct EffectBank {
  std::vector<Spring> springs;
  std::vector<Wall> walls;
  std::vector<Damper> dampers;
  std::vector<Texture> textures;

  // The sum of every built-in effect's force for one input.
  double force_N(const EffectInput& input) const noexcept {
    double force_N = 0.0;
    for (const Spring& e : springs) force_N += e.force_N(input);
    for (const Wall& e : walls) force_N += e.force_N(input);
    for (const Damper& e : dampers) force_N += e.force_N(input);
    for (const Texture& e : textures) force_N += e.force_N(input);
    return force_N;
  }
};

}  // namespace hapscene
