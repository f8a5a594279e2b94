#pragma once
// What the live view draws of a 1-D scene beside its trace: each wall's solid side and
// each texture's fields along the workspace (GET /api/scene's "shapes"), and the static
// force curve, the open-loop force at rest across the workspace ("force_curve").
#include <nlohmann/json.hpp>

#include "engine/scene/scene.hpp"

namespace hapscene {

// [{"kind": "wall", "position_m", "solid": "above"|"below"},
//  {"kind": "texture", "fields_m": [[from, to], ...]}]: the enabled walls and textures, in
// the file's order; a texture's fields within the scene's workspace, to 0.05 mm (at most
// kMaxSketchFields, then "fields_m" is cut there and "more_fields" is true).
nlohmann::json capstan_shapes_json(const Scene& scene);
inline constexpr std::size_t kMaxSketchFields = 500;

// {"x_m": [...], "force_N": [...], "output_N": [...]}: what the scene asks for and what
// the device would be commanded at rest (v = 0, t = 0, fresh script instances: probe's
// open loop) every 0.5 mm across the workspace; points where a script faulted are left
// out. Null, with "force_curve_note" saying why, when the scan could not be made (a
// script too slow for it).
nlohmann::json static_force_curve_json(const Scene& scene, std::string* note);

}  // namespace hapscene
