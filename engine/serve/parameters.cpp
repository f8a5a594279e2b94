#include "engine/serve/parameters.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/harness/planar_bound.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/harness/validate.hpp"
#include "engine/serve/json_text_edit.hpp"

namespace hapscene {
namespace {

// A JSON number, or a string with a unit of `quantity`, in SI (NaN when it is neither).
double value_in_si(const nlohmann::json& value, Quantity quantity) {
  if (value.is_number()) return value.get<double>();
  if (value.is_string()) {
    const QuantityParse parsed = parse_quantity_as(value.get<std::string>(), quantity);
    if (parsed.ok) return parsed.value_si;
  }
  return std::nan("");
}

// The device's limits a slider may span.
template <int N>
struct Limits {
  double max_force_N{};
  double low_m[N]{};   // workspace per axis
  double high_m[N]{};
  double stiffness_N_per_m{};
  const char* stiffness_from{};
  double rate_hz{};
};

template <int N>
Limits<N> limits_of(const SceneOf<N>& scene) {
  Limits<N> limits;
  limits.max_force_N = scene.safety.max_force_N;
  for (int i = 0; i < N; ++i) {
    limits.low_m[i] = component(scene.safety.workspace_min_m, i);
    limits.high_m[i] = component(scene.safety.workspace_max_m, i);
  }
  limits.rate_hz = scene.rate_hz;
  if constexpr (N == 1) {
    // The stiffest passive sampled wall for this device and rate (what validate judges by).
    const PassivityBound bound = passivity_bound(scene.device, scene.period_s);
    limits.stiffness_N_per_m = bound.N_per_m;
    limits.stiffness_from = "the passivity bound of this device and rate (validate)";
  } else {
    // The force limit reached 5 mm into a shape.
    limits.stiffness_N_per_m = scene.safety.max_force_N / 0.005;
    limits.stiffness_from = "the force limit reached at 5 mm of penetration";
  }
  return limits;
}

// The pose bounds a shape's stiffness range is judged on (each costs an inverse
// kinematics and 72 directions): at most this many, whatever the number of edges.
constexpr std::size_t kMaxBoundaryPoints = 512;

// Points evenly spaced along a closed outline, `count` of them, by arc length.
std::vector<Vec2> along_outline(const std::vector<Vec2>& corners, std::size_t count) {
  std::vector<Vec2> out;
  double perimeter_m = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) perimeter_m += norm(corners[(i + 1) % corners.size()] - corners[i]);
  if (!(perimeter_m > 0.0) || count == 0) return corners.empty() ? out : std::vector<Vec2>{corners.front()};
  const double step_m = perimeter_m / static_cast<double>(count);
  double next_m = 0.0;    // arc length of the next point
  double start_m = 0.0;   // arc length at the current edge's start
  for (std::size_t i = 0; i < corners.size() && out.size() < count; ++i) {
    const Vec2 a = corners[i];
    const Vec2 b = corners[(i + 1) % corners.size()];
    const double length_m = norm(b - a);
    while (next_m < start_m + length_m && out.size() < count) {
      out.push_back(a + (b - a) * ((next_m - start_m) / length_m));
      next_m += step_m;
    }
    start_m += length_m;
  }
  return out;
}

}  // namespace

// Points of a 2-D shape's boundary, where its stiffness acts (a wall's line across the
// workspace box; a box's or polygon's edges; a circle's rim), about every 2 mm; at most
// kMaxBoundaryPoints (a polygon of many short edges: evenly along its outline).
std::vector<Vec2> stiffness_bound_points(const PlanarShapeGeometry& shape, const PlanarScene& scene) {
  constexpr double kStep_m = 0.002;
  constexpr int kMaxPerEdge = 128;
  std::vector<Vec2> out;
  const auto along = [&](const Vec2& a, const Vec2& b) {
    const int steps = std::clamp(static_cast<int>(std::ceil(norm(b - a) / kStep_m)), 1, kMaxPerEdge);
    for (int k = 0; k <= steps; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / steps));
  };
  const Vec2 low = scene.safety.workspace_min_m;
  const Vec2 high = scene.safety.workspace_max_m;
  switch (shape.kind) {
    case PlanarShapeKind::wall: {
      // The line through point_m along the normal's perpendicular, clipped to the workspace box.
      const Vec2 d{{-shape.normal[1], shape.normal[0]}};
      double t0 = -INFINITY, t1 = INFINITY;
      for (int i = 0; i < 2; ++i) {
        if (std::fabs(d[i]) < 1e-12) {
          if (shape.point_m[i] < low[i] || shape.point_m[i] > high[i]) return out;
          continue;
        }
        const double a = (low[i] - shape.point_m[i]) / d[i], b = (high[i] - shape.point_m[i]) / d[i];
        t0 = std::fmax(t0, std::fmin(a, b));
        t1 = std::fmin(t1, std::fmax(a, b));
      }
      if (t0 <= t1) along(shape.point_m + d * t0, shape.point_m + d * t1);
      break;
    }
    case PlanarShapeKind::circle: {
      const int steps = std::clamp(static_cast<int>(std::ceil(2.0 * 3.14159265358979 * shape.radius_m / kStep_m)), 8, 4 * kMaxPerEdge);
      for (int k = 0; k < steps; ++k) {
        const double angle = 2.0 * 3.14159265358979 * k / steps;
        out.push_back(shape.center_m + Vec2{{std::cos(angle), std::sin(angle)}} * shape.radius_m);
      }
      break;
    }
    case PlanarShapeKind::box:
    case PlanarShapeKind::polygon:
      // Each edge about every 2 mm, ends included; too many points: evenly along the outline.
      if (shape.points_m.size() <= kMaxBoundaryPoints / 2) {
        for (std::size_t i = 0; i < shape.points_m.size(); ++i) along(shape.points_m[i], shape.points_m[(i + 1) % shape.points_m.size()]);
      }
      if (out.size() > kMaxBoundaryPoints || out.empty()) out = along_outline(shape.points_m, kMaxBoundaryPoints);
      break;
  }
  return out;
}

namespace {

// The smallest per-pose stiffness bound over `points` (false when none is a pose force is
// rendered at).
bool lowest_bound(const PlanarScene& scene, const std::vector<Vec2>& points, PlanarPoseBound* lowest) {
  bool any = false;
  for (const Vec2& p : points) {
    PlanarPoseBound pose;
    if (!planar_pose_bound_at(scene, p, &pose)) continue;
    if (!any || pose.bound_N_per_m < lowest->bound_N_per_m) *lowest = pose;
    any = true;
  }
  return any;
}

// A 2-D effect's stiffness range: 0 to the smallest stiffness bound where it acts (a
// shape: on its boundary inside the workspace; a spring: anywhere in the workspace, the
// grid validate uses), with that pose. `shape` null: a spring.
void set_pose_bounded_stiffness(const PlanarScene& scene, const PlanarShapeGeometry* shape, LiveParameter* p) {
  PlanarPoseBound pose;
  bool found = false;
  std::string where;
  if (shape != nullptr) {
    found = lowest_bound(scene, stiffness_bound_points(*shape, scene), &pose);
    where = "on the shape's boundary";
  }
  if (!found) {
    const PlanarStiffnessBound grid = planar_stiffness_bound(scene);
    if (grid.poses.empty()) return;  // nowhere to judge: the force-limit range stays
    pose = grid.lowest;
    found = true;
    where = shape != nullptr ? "in the workspace (the shape's boundary is where no force is rendered)"
                             : "in the workspace (a spring acts everywhere)";
  }
  p->min = 0.0;
  p->max = pose.bound_N_per_m;
  p->bound_pose = true;
  p->bound_at_m = pose.x_m;
  p->bound_name = pose.name;
  p->bound_N_per_m = pose.bound_N_per_m;
  p->range_from = printf_string("the stiffness bound %s at (%.1f, %.1f) mm, the lowest %s", pose.name,
                                pose.x_m[0] * 1e3, pose.x_m[1] * 1e3, where.c_str());
}

// The slider's range for a value of `quantity` on axis `axis` (-1: not a component). A
// length is a size (0 to the workspace's width) when `size`, else a place in the workspace.
template <int N>
void set_range(const Limits<N>& limits, bool size, int axis, LiveParameter* p) {
  const int a = axis < 0 ? 0 : axis;
  const double span_m = limits.high_m[a] - limits.low_m[a];
  switch (p->quantity) {
    case Quantity::length_m:
      if (size) {
        p->min = 0.0;
        p->max = span_m;
        p->range_from = "0 to the workspace's width";
      } else {
        p->min = limits.low_m[a];
        p->max = limits.high_m[a];
        p->range_from = N == 1 ? std::string("the workspace") : std::string("the workspace in ") + kAxisNames[a];
      }
      break;
    case Quantity::stiffness_N_per_m:
      p->min = 0.0;
      p->max = limits.stiffness_N_per_m;
      p->range_from = limits.stiffness_from;
      break;
    case Quantity::damping_N_s_per_m:
      p->min = 0.0;
      p->max = limits.max_force_N / 1.0;
      p->range_from = "the force limit reached at 1 m/s";
      break;
    case Quantity::force_N:
      p->min = -limits.max_force_N;
      p->max = limits.max_force_N;
      p->range_from = "the force limit";
      break;
    case Quantity::time_s:
      p->min = 0.0;
      p->max = 10.0;
      p->range_from = "0 to 10 s";
      break;
    case Quantity::frequency_Hz:
      p->min = 0.0;
      p->max = limits.rate_hz / 2.0;
      p->range_from = "0 to half the tick rate";
      break;
    default:
      p->min = std::min(0.0, 2.0 * p->value);
      p->max = std::max(1.0, 2.0 * p->value);
      p->range_from = "0 to twice the value";
      break;
  }
  // The range always holds the value as it is.
  if (std::isfinite(p->value)) {
    p->min = std::min(p->min, p->value);
    p->max = std::max(p->max, p->value);
  }
}

std::string axis_label(const std::string& key, int axis) {
  return axis < 0 ? key : key + " " + kAxisNames[axis];
}

// The string form of a unit written after a number ("10 mm" -> "mm"), or "" when none.
std::string unit_of(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  (void)std::strtod(begin, &end);
  if (end == begin) return {};
  std::string unit(end);
  const auto first = unit.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return unit.substr(first);
}

std::string shortest(double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::string("0");
}

// A number for a string with a unit: 12 significant digits, so 0.012 m reads "12 mm".
std::string in_unit(double value, const std::string& unit, Quantity quantity, bool* ok) {
  const QuantityParse one = parse_quantity_as("1 " + unit, quantity);
  *ok = one.ok && one.value_si != 0.0;
  if (!*ok) return {};
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.12g", value / one.value_si);
  return std::string(buffer) + " " + unit;
}

// The parameter's path as JSON pointer tokens from the root.
std::vector<std::string> tokens_of(std::size_t effect, const std::string& parameter) {
  std::vector<std::string> tokens{"effects", std::to_string(effect)};
  std::size_t start = 0;
  for (;;) {
    const std::size_t slash = parameter.find('/', start);
    tokens.push_back(parameter.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return tokens;
}

}  // namespace

template <int N>
std::vector<LiveParameter> live_parameters(const nlohmann::json& document, const SceneOf<N>& scene) {
  std::vector<LiveParameter> out;
  const Limits<N> limits = limits_of(scene);
  // The compiled scripts, in file order (the scene lists enabled effects as written).
  std::vector<const ScriptProgram*> programs;
  for (const auto& effect : scene.effects) {
    if (const auto* script = std::get_if<ScriptEffect>(&effect)) programs.push_back(script->program.get());
  }
  std::size_t next_program = 0;
  // 2-D: the scene's shapes, grouped by kind in file order (planar_shape_list), and how
  // many of each kind the file's enabled effects have had so far.
  std::vector<PlanarShapeGeometry> shapes;
  if constexpr (N > 1) shapes = planar_shape_list(scene);
  int seen_of_kind[4] = {0, 0, 0, 0};
  const auto effects = document.find("effects");
  if (effects == document.end() || !effects->is_array()) return out;
  for (std::size_t index = 0; index < effects->size(); ++index) {
    const nlohmann::json& effect = (*effects)[index];
    if (!effect.is_object() || !effect.contains("type") || !effect["type"].is_string()) continue;
    const std::string type = effect["type"].get<std::string>();
    const bool enabled = !effect.contains("enabled") || effect["enabled"] != false;
    if (type == "script") {
      if (!enabled) continue;
      if (next_program >= programs.size()) continue;
      const ScriptProgram& program = *programs[next_program++];
      for (const ScriptParam& param : program.params) {
        if (param.kind != ScriptParam::Kind::number) continue;
        LiveParameter p;
        p.effect = index;
        p.type = type;
        p.parameter = "params/" + param.name;
        p.label = param.name;
        p.quantity = param.has_unit ? param.quantity : Quantity::dimensionless;
        p.value = param.value_si;
        p.written = param.overridden;
        // A script's lengths named as the built-in sizes are sizes too.
        const bool size = param.name == "width" || param.name == "spacing" || param.name == "radius";
        set_range(limits, size, -1, &p);
        out.push_back(std::move(p));
      }
      continue;
    }
    // The type's declaration (engine/effects/effect_keys.hpp): its slidable keys.
    const auto& declarations = SceneParts<N>::Effects::kDeclarations;
    const auto declaration = std::find_if(declarations.begin(), declarations.end(),
                                          [&](const EffectDeclaration& d) { return type == d.type; });
    if (declaration == declarations.end()) continue;
    // 2-D: this effect's shape in the scene (null: not a shape, or disabled).
    const PlanarShapeGeometry* shape = nullptr;
    if constexpr (N > 1) {
      static const char* const kKinds[4] = {"wall", "box", "circle", "polygon"};
      static const PlanarShapeKind kKindOf[4] = {PlanarShapeKind::wall, PlanarShapeKind::box, PlanarShapeKind::circle,
                                                 PlanarShapeKind::polygon};
      for (int k = 0; k < 4 && enabled; ++k) {
        if (type != kKinds[k]) continue;
        int rank = seen_of_kind[k]++;
        for (const PlanarShapeGeometry& g : shapes) {
          if (g.kind == kKindOf[k] && rank-- == 0) {
            shape = &g;
            break;
          }
        }
      }
    }
    for (const EffectKey& key : declaration->keys) {
      if (!key.slidable) continue;
      const std::string name(key.name);
      const bool written = effect.contains(name);
      const int components = component_count(key, N);
      for (int axis = 0; axis < components; ++axis) {
        LiveParameter p;
        p.effect = index;
        p.type = type;
        p.quantity = key.quantity;
        p.written = written;
        const int shown_axis = components > 1 ? axis : -1;
        p.parameter = shown_axis < 0 ? name : name + "/" + std::to_string(axis);
        p.label = axis_label(name, shown_axis);
        const std::string from(key.fallback_from);
        if (written) {
          const nlohmann::json& value = effect[name];
          p.value = shown_axis < 0 ? value_in_si(value, key.quantity)
                                   : (value.is_array() && value.size() > static_cast<std::size_t>(axis)
                                          ? value_in_si(value[static_cast<std::size_t>(axis)], key.quantity)
                                          : std::nan(""));
        } else if (!from.empty() && effect.contains(from)) {
          p.value = value_in_si(effect[from], key.quantity);
        } else {
          p.value = key.fallback_si;
        }
        if (!std::isfinite(p.value)) continue;
        if constexpr (N > 1) {
          if (p.quantity == Quantity::stiffness_N_per_m && enabled && (shape != nullptr || type == "spring")) {
            set_pose_bounded_stiffness(scene, shape, &p);
          }
        }
        // A length whose range starts at zero is a size (a width, a radius), else a place.
        if (!p.bound_pose) set_range(limits, key.range.min >= 0.0, shown_axis, &p);
        if (p.bound_pose && std::isfinite(p.value)) p.max = std::max(p.max, p.value);  // holds the value
        out.push_back(std::move(p));
      }
    }
  }
  return out;
}

std::string with_parameter(std::string_view text, const std::vector<LiveParameter>& parameters, std::size_t effect,
                           const std::string& parameter, const nlohmann::json& value) {
  const auto found = std::find_if(parameters.begin(), parameters.end(), [&](const LiveParameter& p) {
    return p.effect == effect && p.parameter == parameter;
  });
  if (found == parameters.end()) {
    throw InputError("/effects/" + std::to_string(effect) + "/" + parameter + ": no such parameter (GET /api/scene lists them)");
  }
  const std::vector<std::string> tokens = tokens_of(effect, parameter);
  std::string value_json;
  if (value.is_string()) {
    value_json = json_string_literal(value.get<std::string>());
  } else if (value.is_number()) {
    const double si = value.get<double>();
    if (!std::isfinite(si)) throw InputError("value: must be a finite number");
    value_json = shortest(si);
    // Written with a unit before: the same unit again.
    JsonSpan span;
    if (find_json_value(text, tokens, &span) && text[span.begin] == '"') {
      const std::string before = nlohmann::json::parse(text.substr(span.begin, span.end - span.begin)).get<std::string>();
      const std::string unit = unit_of(before);
      bool ok = false;
      const std::string with_unit = unit.empty() ? std::string() : in_unit(si, unit, found->quantity, &ok);
      if (ok) value_json = json_string_literal(with_unit);
    }
  } else {
    throw InputError("value: expected a number (SI) or a string with a unit, got " + std::string(value.type_name()));
  }
  return set_json_value(text, tokens, value_json);
}

nlohmann::json parameter_to_json(const LiveParameter& p) {
  return {{"effect", p.effect},
          {"type", p.type},
          {"parameter", p.parameter},
          {"label", p.label},
          {"quantity", std::string(quantity_name(p.quantity))},
          {"unit", std::string(si_unit(p.quantity))},
          {"value", p.value},
          {"min", p.min},
          {"max", p.max},
          {"range_from", p.range_from},
          {"written", p.written},
          {"bound_at_m", p.bound_pose ? nlohmann::json::array({p.bound_at_m[0], p.bound_at_m[1]}) : nlohmann::json(nullptr)},
          {"bound", p.bound_pose ? nlohmann::json(p.bound_name) : nlohmann::json(nullptr)},
          {"bound_N_per_m", p.bound_pose ? nlohmann::json(p.bound_N_per_m) : nlohmann::json(nullptr)}};
}

#define HAPSCENE_LIVE_PARAMETERS(N) \
  template std::vector<LiveParameter> live_parameters<N>(const nlohmann::json&, const SceneOf<N>&);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_LIVE_PARAMETERS)
#undef HAPSCENE_LIVE_PARAMETERS

}  // namespace hapscene
