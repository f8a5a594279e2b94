#pragma once
// The live view's parameters: every numeric key of every effect of an environment (the
// built-in effects' keys, written or left at their defaults, vector keys per component)
// and every numeric parameter of every script, with its quantity, its value in SI and a
// safe range for a slider taken from the device's limits; and the environment text with
// one of them changed, edited in place (engine/serve/json_text_edit.hpp) so that saving
// it keeps the file's layout.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/units.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct LiveParameter {
  std::size_t effect{};      // index in the file's "effects" array (as in /effects/N)
  std::string type;          // the effect's "type": "wall", "box", "script"
  std::string parameter;     // relative to the effect: "stiffness", "min/0", "params/height"
  std::string label;         // for people: "stiffness", "min x", "height"
  Quantity quantity{Quantity::dimensionless};
  double value{};            // SI
  double min{};              // the slider's range, SI (always holds `value`)
  double max{};
  std::string range_from;    // what the range comes from ("the device's workspace", ...)
  bool written{};            // present in the file (else the loader's default)
  // 2-D stiffness: the pose whose stiffness bound is the range's max (else none).
  bool bound_pose{};
  Vec2 bound_at_m{};
  std::string bound_name;    // "2b/T" or "2fc/D"
  double bound_N_per_m{};    // the bound there (max, unless the value is above it)
};

// The parameters of `document` (the environment's JSON) compiled as `scene`, in file order.
template <int N>
std::vector<LiveParameter> live_parameters(const nlohmann::json& document, const SceneOf<N>& scene);

// `text` with parameter `parameter` of effect `effect` set to `value`: a number (SI) or a
// string with a unit ("600 N/m"). A number replacing a value written with a unit is
// written in that unit ("12 mm" for 0.012 over "10 mm"). Throws InputError (a bad
// request: no such effect or parameter, a value of another JSON type); whether the value
// itself is acceptable is the loader's to say.
std::string with_parameter(std::string_view text, const std::vector<LiveParameter>& parameters, std::size_t effect,
                           const std::string& parameter, const nlohmann::json& value);

// The poses a 2-D shape's stiffness range is judged on: its boundary inside the
// workspace about every 2 mm, at most 512 points whatever its number of edges (a
// 10,000-edge polygon is described in milliseconds, not seconds).
std::vector<Vec2> stiffness_bound_points(const PlanarShapeGeometry& shape, const PlanarScene& scene);

// The parameter as JSON for GET /api/scene.
nlohmann::json parameter_to_json(const LiveParameter& parameter);

}  // namespace hapscene
