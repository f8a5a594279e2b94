#pragma once
// Load warnings for built-in effects that can never give a force in the scene: a zero
// gain, or a wall whose solid side lies wholly outside the workspace (with the likely
// cause: a unit slip, the environment's own safety workspace, or a wall on the edge).
#include <string>

#include <nlohmann/json.hpp>

#include "engine/scene/scene.hpp"

namespace hapscene {

// The warning for `effect` ("(wall): position 20 m puts ..."), or empty when it can act.
// `written` is the effect's JSON object (to tell a plain number from one with a unit);
// `scene` must have its device and safety set.
std::string inert_effect_warning(const Effect& effect, const nlohmann::json& written, const Scene& scene);

}  // namespace hapscene
