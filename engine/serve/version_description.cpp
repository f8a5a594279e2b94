#include "engine/serve/version_description.hpp"

#include "engine/harness/planar_shape_list.hpp"
#include "engine/load/environment.hpp"
#include "engine/serve/capstan_sketch.hpp"
#include "engine/serve/live_view.hpp"

namespace hapscene {

using json = nlohmann::json;

json axes_json(double value) { return value; }
json axes_json(const Vec2& value) { return json::array({value[0], value[1]}); }

template <int N>
std::unique_ptr<LoadedSceneOf<N>> load_version(const std::string& text, const std::string& path,
                                               const std::string& base_dir) {
  return make_loaded_scene<N>(compile_environment_of<N>(text, path, base_dir).scene);
}

template <int N>
VersionDescription describe_version(const SceneOf<N>& scene, const std::string& text, const std::string& path,
                                    std::uint64_t stride) {
  const json document = json::parse(text);
  VersionDescription out;
  out.parameters = live_parameters<N>(document, scene);
  json device{{"name", scene.device.name},
              {"max_force_N", scene.safety.max_force_N},
              {"slew_limit_N_per_s", scene.safety.slew_limit_N_per_s},
              {"soft_start_s", scene.safety.soft_start_s},
              {"workspace_min_m", axes_json(scene.safety.workspace_min_m)},
              {"workspace_max_m", axes_json(scene.safety.workspace_max_m)}};
  json effects = json::array();
  if (document.contains("effects") && document["effects"].is_array()) {
    for (std::size_t i = 0; i < document["effects"].size(); ++i) {
      const json& effect = document["effects"][i];
      json item{{"effect", i}};
      item["type"] = effect.is_object() && effect.contains("type") ? effect["type"] : json(nullptr);
      item["enabled"] = !(effect.is_object() && effect.contains("enabled") && effect["enabled"] == false);
      if (effect.is_object() && effect.contains("file")) item["file"] = effect["file"];
      effects.push_back(item);
    }
  }
  json shapes = json::array();
  json force_curve = nullptr;
  std::string force_curve_note;
  if constexpr (N == 1) {
    shapes = capstan_shapes_json(scene);
    force_curve = static_force_curve_json(scene, &force_curve_note);
  } else {
    for (const PlanarShapeGeometry& shape : planar_shape_list(scene)) {
      json s{{"kind", planar_shape_kind_name(shape.kind)}, {"solid_inside", shape.solid_inside}};
      if (shape.kind == PlanarShapeKind::wall) {
        s["point_m"] = axes_json(shape.point_m);
        s["normal"] = axes_json(shape.normal);
      } else if (shape.kind == PlanarShapeKind::circle) {
        s["center_m"] = axes_json(shape.center_m);
        s["radius_m"] = shape.radius_m;
      } else {
        json points = json::array();
        for (const Vec2& p : shape.points_m) points.push_back(axes_json(p));
        s["points_m"] = points;
      }
      shapes.push_back(s);
    }
  }
  json params = json::array();
  for (const LiveParameter& p : out.parameters) params.push_back(parameter_to_json(p));
  out.scene_json = json{{"name", scene.name},
                        {"file", path},
                        {"axes", N},
                        {"rate_hz", scene.rate_hz},
                        {"device", device},
                        {"stream", {{"events_per_s", kLiveEventsPerSecond}, {"stride", stride}}},
                        {"effects", effects},
                        {"parameters", params},
                        {"shapes", shapes}};
  if constexpr (N == 1) {
    out.scene_json["force_curve"] = force_curve;
    if (!force_curve_note.empty()) out.scene_json["force_curve_note"] = force_curve_note;
  }
  return out;
}

#define HAPSCENE_VERSION_DESCRIPTION(N)                                                                        \
  template std::unique_ptr<LoadedSceneOf<N>> load_version<N>(const std::string&, const std::string&,          \
                                                             const std::string&);                             \
  template VersionDescription describe_version<N>(const SceneOf<N>&, const std::string&, const std::string&, \
                                                  std::uint64_t);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_VERSION_DESCRIPTION)
#undef HAPSCENE_VERSION_DESCRIPTION

}  // namespace hapscene
