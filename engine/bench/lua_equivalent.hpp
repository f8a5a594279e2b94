#pragma once
// The same lab environment written as a Lua script, for `hapscene bench`'s Lua rows:
// scripts/spring.lua and scripts/texture.lua with the scene's parameters, and inline
// sources with exactly the lab formulas for the wall and the damper (scripts/wall.lua is
// a different, harder wall).
#include <optional>

#include "engine/scene/scene.hpp"

namespace hapscene {

// A scene computing the same force as `scene` (one lab effect) through a script effect,
// at the same rate on the same device; empty when the scene is not a single lab effect.
// `scripts_dir` holds spring.lua and texture.lua. Throws InputError when a script does
// not load.
std::optional<Scene> lua_equivalent(const Scene& scene, const std::string& scripts_dir);

}  // namespace hapscene
