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

// The same for a 2-D effect in a planar scene: a zero gain, a shape whose solid lies
// wholly outside the workspace box ("(circle): the solid disc ... lies wholly outside the
// workspace [...] x [...] m, so the circle never acts"), or a cage the workspace lies
// wholly inside. The test is the one add_effect uses (can_act_within on the workspace box).
std::string inert_effect_warning(const PlanarEffect& effect, const nlohmann::json& written, const PlanarScene& scene);

}  // namespace hapscene
