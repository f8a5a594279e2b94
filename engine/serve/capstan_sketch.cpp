#include "engine/serve/capstan_sketch.hpp"

#include <cmath>
#include <exception>
#include <type_traits>
#include <variant>
#include <vector>

#include "engine/harness/open_loop.hpp"

namespace hapscene {
namespace {

constexpr double kFieldResolution_m = 0.05e-3;  // where a field's edges are looked for
constexpr double kCurveStep_m = 0.5e-3;

// The texture's fields within [low, high], each an interval of the points in a field.
nlohmann::json texture_fields(const Texture& texture, double low_m, double high_m, bool* more) {
  nlohmann::json fields = nlohmann::json::array();
  const auto steps = static_cast<long>(std::floor((high_m - low_m) / kFieldResolution_m));
  bool inside = false;
  double from_m = 0.0;
  for (long i = 0; i <= steps + 1; ++i) {
    const double x_m = std::min(high_m, low_m + static_cast<double>(i) * kFieldResolution_m);
    const bool in = i <= steps && texture.in_field(x_m);
    if (in && !inside) from_m = x_m;
    if (!in && inside) {
      if (fields.size() == kMaxSketchFields) {
        *more = true;
        break;
      }
      fields.push_back({from_m, std::min(high_m, x_m)});
    }
    inside = in;
  }
  return fields;
}

}  // namespace

nlohmann::json capstan_shapes_json(const Scene& scene) {
  nlohmann::json shapes = nlohmann::json::array();
  const double low_m = scene.safety.workspace_min_m;
  const double high_m = scene.safety.workspace_max_m;
  for (const Effect& effect : scene.effects) {
    std::visit(
        [&](const auto& e) {
          using Type = std::decay_t<decltype(e)>;
          if constexpr (std::is_same_v<Type, Wall>) {
            shapes.push_back({{"kind", "wall"}, {"position_m", e.position_m}, {"solid", e.solid_above ? "above" : "below"}});
          } else if constexpr (std::is_same_v<Type, Texture>) {
            bool more = false;
            nlohmann::json texture{{"kind", "texture"}, {"fields_m", texture_fields(e, low_m, high_m, &more)}};
            if (more) texture["more_fields"] = true;
            shapes.push_back(texture);
          }
        },
        effect);
  }
  return shapes;
}

nlohmann::json static_force_curve_json(const Scene& scene, std::string* note) {
  const double low_m = scene.safety.workspace_min_m;
  const double high_m = scene.safety.workspace_max_m;
  std::vector<double> x_m;
  for (long i = 0; low_m + static_cast<double>(i) * kCurveStep_m <= high_m + 1e-12; ++i) {
    x_m.push_back(low_m + static_cast<double>(i) * kCurveStep_m);
  }
  try {
    OpenLoop open_loop(scene, 0.0);
    const OpenLoopScan scan = open_loop.scan(x_m, 0.0);
    nlohmann::json curve{{"x_m", nlohmann::json::array()}, {"force_N", nlohmann::json::array()},
                         {"output_N", nlohmann::json::array()}};
    for (std::size_t i = 0; i < x_m.size(); ++i) {
      if (!scan.script_faulted.empty() && scan.script_faulted[i]) continue;
      const double force_N = scan.force_N[i];
      const double output_N = open_loop.output_N(x_m[i], force_N);
      if (!std::isfinite(force_N) || !std::isfinite(output_N)) continue;
      curve["x_m"].push_back(x_m[i]);
      curve["force_N"].push_back(force_N);
      curve["output_N"].push_back(output_N);
    }
    return curve;
  } catch (const std::exception& error) {
    *note = error.what();
    return nullptr;
  }
}

}  // namespace hapscene
