#include "engine/load/effect_warnings.hpp"

#include <limits>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "engine/base/object_reader.hpp"
#include "engine/base/units.hpp"

namespace hapscene {
namespace {

// An effect of either dimension whose gain is zero does nothing anywhere: its warning, or
// empty. (A built-in effect that cannot act even in an unbounded workspace has a zero gain.)
template <typename Type, typename Bound>
std::string zero_gain_warning(const Type& effect, const Bound& unbounded_low, const Bound& unbounded_high) {
  if (effect.can_act_within(unbounded_low, unbounded_high)) return "";
  // The gain, as the type declares it (engine/effects/effect_keys.hpp).
  constexpr const EffectKey* gain = gain_key(declaration_of<Type>());
  static_assert(gain != nullptr, "a built-in effect declares the key whose zero leaves it idle");
  return std::string("(") + Type::kType + "): " + std::string(gain->name) + " 0 " + std::string(si_unit(gain->quantity)) +
         ", so the " + Type::kType +
         " never acts (\"enabled\": false leaves an effect out without a warning)";
}

// The warning for any effect of a scene of either dimension: scripts never (their force
// is known only by running them), a zero gain, then what the type's own check adds
// (`placed`: the effect's solid beyond the workspace).
template <typename Variant, typename Bound, typename Placed>
std::string effect_warning(const Variant& effect, const Bound& unbounded_low, const Bound& unbounded_high,
                           Placed placed) {
  return std::visit(
      [&](const auto& e) -> std::string {
        using Type = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<Type, ScriptEffect>) {
          return "";
        } else {
          std::string zero = zero_gain_warning(e, unbounded_low, unbounded_high);
          return zero.empty() ? placed(e) : zero;
        }
      },
      effect);
}

std::string interval(double low_m, double high_m) {
  return "[" + format_number(low_m) + ", " + format_number(high_m) + "] m";
}

// Whether a length was written without a unit (a number, or a string such as "20"): then
// it is metres, and 20 meant as 20 mm is 20 m. A vector ([x, y]) or a list of them (a
// polygon's points) counts when every number in it was.
bool without_unit(const nlohmann::json& value) {
  if (value.is_number()) return true;
  if (value.is_string()) {
    const QuantityParse parsed = parse_quantity(value.get<std::string>());
    return parsed.ok && parsed.quantity == Quantity::dimensionless;
  }
  if (!value.is_array() || value.empty()) return false;
  for (const nlohmann::json& item : value) {
    if (!without_unit(item)) return false;
  }
  return true;
}
bool written_without_unit(const nlohmann::json& written, const char* key) {
  if (!written.is_object()) return false;
  const auto value = written.find(key);
  return value != written.end() && without_unit(*value);
}

// The hint for a unit slip, for effects of either dimension: "; did you mean ...?" when
// the effect's lengths written without a unit, read in mm (or else cm), put it inside the
// device's own workspace, though as written (metres) they do not; noting when even then
// it would not act within the environment's narrower /safety/workspace. `in_device(scale)`
// and `acts(scale)` judge the effect with those lengths times `scale`; `written_as(unit)`
// says how they would be written in that unit.
template <typename InDevice, typename Acts, typename WrittenAs>
std::string unit_slip_hint(InDevice in_device, Acts acts, WrittenAs written_as) {
  if (in_device(1.0)) return "";
  for (const auto& [unit, scale] : {std::pair{"mm", 1e-3}, std::pair{"cm", 1e-2}}) {
    if (!in_device(scale)) continue;
    std::string hint = "; did you mean " + written_as(unit) + "?";
    if (!acts(scale)) hint += " (even there it would not act within /safety/workspace)";
    return hint;
  }
  return "";
}

std::string wall_warning(const Wall& wall, const nlohmann::json& written, const Scene& scene) {
  const double low_m = scene.safety.workspace_min_m;
  const double high_m = scene.safety.workspace_max_m;
  if (wall.can_act_within(low_m, high_m)) return "";
  const DeviceLimits& device = scene.device.limits;
  const bool narrowed = low_m != device.workspace_min_m || high_m != device.workspace_max_m;
  // Name the workspace that excludes the wall: the environment's own, when it set one.
  const std::string workspace =
      narrowed ? "the environment's safety workspace " + interval(low_m, high_m) + " (/safety/workspace; the device's is " +
                     interval(device.workspace_min_m, device.workspace_max_m) + ")"
               : "the workspace " + interval(low_m, high_m);
  const char* side = wall.solid_above ? "above" : "below";
  std::string message = "(wall): position " + format_number(wall.position_m) + " m ";
  if (wall.position_m == (wall.solid_above ? high_m : low_m)) {
    message += std::string("is the ") + (wall.solid_above ? "upper" : "lower") + " edge of " + workspace +
               ", so its solid side (" + side + ") lies wholly outside it and the wall never acts";
    return message;
  }
  message += std::string("puts the solid side (") + side + ") wholly outside " + workspace + ", so the wall never acts";
  // A unit slip is likely only for a plain number beyond the device's own travel; the hint
  // is given when the value read in mm (or cm) lies inside the device's workspace.
  if (!written_without_unit(written, "position")) return message;
  const auto moved = [&](double scale) {
    Wall w = wall;
    w.position_m *= scale;
    return w;
  };
  return message + unit_slip_hint(
                       [&](double scale) {
                         const double x_m = moved(scale).position_m;
                         return x_m > device.workspace_min_m && x_m < device.workspace_max_m;
                       },
                       [&](double scale) { return moved(scale).can_act_within(low_m, high_m); },
                       [&](const char* unit) { return "\"" + format_number(wall.position_m) + " " + unit + "\""; });
}

// A spring whose centre, written without a unit, lies outside the device's workspace: it
// pulls the handle toward a place it cannot reach, everywhere (likely "center": 10 meant
// as 10 mm). The warning, with the unit-slip hint when mm (or cm) put the centre inside.
std::string spring_warning(const Spring& spring, const nlohmann::json& written, const Scene& scene) {
  const DeviceLimits& device = scene.device.limits;
  const auto inside = [&](double scale) {
    const double x_m = spring.center_m * scale;
    return x_m >= device.workspace_min_m && x_m <= device.workspace_max_m;
  };
  if (!written_without_unit(written, "center") || inside(1.0)) return "";
  return "(spring): center " + format_number(spring.center_m) + " m lies outside the workspace " +
         interval(device.workspace_min_m, device.workspace_max_m) +
         ", so the spring pulls the handle toward a place it cannot reach" +
         unit_slip_hint(inside, inside, [&](const char* unit) {
           return "\"" + format_number(spring.center_m) + " " + unit + "\"";
         });
}

// "[-0.07, 0.04] x [0.09, 0.165] m": a box of the plane.
std::string box_text(const Vec2& low_m, const Vec2& high_m) {
  return "[" + format_number(low_m[0]) + ", " + format_number(high_m[0]) + "] x [" + format_number(low_m[1]) + ", " +
         format_number(high_m[1]) + "] m";
}
std::string point_text(const Vec2& p) { return "(" + format_number(p[0]) + ", " + format_number(p[1]) + ")"; }

// The workspace a planar effect is judged against, named: the environment's own when it
// set one (as in 1-D), and "box" when the device's workspace is a polygon (the effect is
// judged against the polygon's bounding box).
std::string planar_workspace_text(const PlanarScene& scene) {
  const Vec2& low_m = scene.safety.workspace_min_m;
  const Vec2& high_m = scene.safety.workspace_max_m;
  const PlanarWorkspace& device = scene.device.limits.workspace;
  Vec2 device_low_m;
  Vec2 device_high_m;
  workspace_bounds(device, &device_low_m, &device_high_m);
  const bool narrowed = low_m != device_low_m || high_m != device_high_m;
  if (narrowed && device.is_box) {
    return "the environment's safety workspace " + box_text(low_m, high_m) + " (/safety/workspace; the device's is " +
           box_text(device_low_m, device_high_m) + ")";
  }
  if (narrowed) return "the environment's safety workspace " + box_text(low_m, high_m) + " (/safety/workspace)";
  return std::string(device.is_box ? "the workspace " : "the box round the workspace ") + box_text(low_m, high_m);
}

// What a 2-D effect's solid is, for the warning ("the solid box [...] x [...] m").
std::string solid_text(const PlanarWall& wall) {
  return "its solid half-plane (the side of the line through " + point_text(wall.point_m) +
         " m away from the normal " + point_text(wall.normal) + ")";
}
std::string solid_text(const PlanarBox& box) {
  return box.solid_inside ? "the solid box " + box_text(box.min_m, box.max_m) : "";
}
std::string solid_text(const PlanarCircle& circle) {
  return circle.solid_inside ? "the solid disc of radius " + format_number(circle.radius_m) + " m about " +
                                   point_text(circle.center_m) + " m"
                             : "";
}
std::string solid_text(const PlanarPolygon& polygon) {
  return polygon.outline.solid_inside()
             ? "the solid polygon of " + std::to_string(polygon.outline.edge_count()) + " points"
             : "";
}

// A 2-D shape's lengths, by key: those written without a unit are what a unit slip
// scales. `scaled(e, keys, scale)` is the shape with those lengths times scale.
std::string length_text(double value_m, const char* unit) { return "\"" + format_number(value_m) + " " + unit + "\""; }
std::string length_text(const Vec2& p_m, const char* unit) {
  return "[" + length_text(p_m[0], unit) + ", " + length_text(p_m[1], unit) + "]";
}
bool has_key(const std::vector<const char*>& keys, const char* key) {
  for (const char* k : keys) {
    if (std::string_view(k) == key) return true;
  }
  return false;
}
PlanarWall scaled(const PlanarWall& wall, const std::vector<const char*>&, double scale) {
  PlanarWall w = wall;
  w.point_m = wall.point_m * scale;
  return w;
}
PlanarBox scaled(const PlanarBox& box, const std::vector<const char*>& keys, double scale) {
  return PlanarBox::make(has_key(keys, "min") ? box.min_m * scale : box.min_m,
                         has_key(keys, "max") ? box.max_m * scale : box.max_m, box.stiffness_N_per_m, box.solid_inside);
}
PlanarCircle scaled(const PlanarCircle& circle, const std::vector<const char*>& keys, double scale) {
  PlanarCircle c = circle;
  if (has_key(keys, "center")) c.center_m = circle.center_m * scale;
  if (has_key(keys, "radius")) c.radius_m = circle.radius_m * scale;
  return c;
}
PlanarPolygon scaled(const PlanarPolygon& polygon, const std::vector<const char*>&, double scale) {
  std::vector<Vec2> points;
  for (int i = 0; i < polygon.outline.edge_count(); ++i) points.push_back(polygon.outline.vertex(i) * scale);
  PlanarPolygon p;
  p.outline = PolygonOutline(points, polygon.outline.solid_inside());
  p.stiffness_N_per_m = polygon.stiffness_N_per_m;
  return p;
}
// Whether the shape's outline meets the box: its solid reaches into it and so does its
// free part (a cage wholly round the box, or far from it, does not).
bool meets_box(const PlanarWall& wall, const Vec2& low, const Vec2& high) { return wall.can_act_within(low, high); }
bool meets_box(const PlanarBox& box, const Vec2& low, const Vec2& high) {
  return box.can_act_within(low, high) && PlanarBox::make(box.min_m, box.max_m, 1.0, !box.solid_inside).can_act_within(low, high);
}
bool meets_box(const PlanarCircle& circle, const Vec2& low, const Vec2& high) {
  PlanarCircle other = circle;
  other.solid_inside = !circle.solid_inside;
  return circle.can_act_within(low, high) && other.can_act_within(low, high);
}
bool meets_box(const PlanarPolygon& polygon, const Vec2& low, const Vec2& high) {
  std::vector<Vec2> points;
  for (int i = 0; i < polygon.outline.edge_count(); ++i) points.push_back(polygon.outline.vertex(i));
  PlanarPolygon other;
  other.outline = PolygonOutline(points, !polygon.outline.solid_inside());
  other.stiffness_N_per_m = 1.0;
  return polygon.can_act_within(low, high) && other.can_act_within(low, high);
}
std::vector<const char*> length_keys(const PlanarWall&) { return {"point"}; }
std::vector<const char*> length_keys(const PlanarBox&) { return {"min", "max"}; }
std::vector<const char*> length_keys(const PlanarCircle&) { return {"center", "radius"}; }
std::vector<const char*> length_keys(const PlanarPolygon&) { return {"points"}; }
std::string written_in(const PlanarWall& wall, const char* key, const char* unit) {
  return std::string("\"") + key + "\": " + length_text(wall.point_m, unit);
}
std::string written_in(const PlanarBox& box, const char* key, const char* unit) {
  return std::string("\"") + key + "\": " + length_text(std::string_view(key) == "min" ? box.min_m : box.max_m, unit);
}
std::string written_in(const PlanarCircle& circle, const char* key, const char* unit) {
  return std::string("\"") + key + "\": " +
         (std::string_view(key) == "center" ? length_text(circle.center_m, unit) : length_text(circle.radius_m, unit));
}
// A polygon's points: the first two, then "..." when there are more than three.
std::string written_in(const PlanarPolygon& polygon, const char*, const char* unit) {
  const int n = polygon.outline.edge_count();
  std::string text = "\"points\": [";
  for (int i = 0; i < n && (i < 2 || n <= 3); ++i) text += (i ? ", " : "") + length_text(polygon.outline.vertex(i), unit);
  return text + (n > 3 ? ", ...]" : "]");
}

// A 2-D shape's unit-slip hint (unit_slip_hint): its lengths written without a unit read
// in mm (or cm) put its outline across the device's workspace box, where as written they
// do not (a cage is not hinted to shrink round nothing).
template <typename Type>
std::string planar_unit_slip_hint(const Type& e, const nlohmann::json& written, const PlanarScene& scene) {
  std::vector<const char*> keys;
  for (const char* key : length_keys(e)) {
    if (written_without_unit(written, key)) keys.push_back(key);
  }
  if (keys.empty()) return "";
  Vec2 device_low;
  Vec2 device_high;
  workspace_bounds(scene.device.limits.workspace, &device_low, &device_high);
  return unit_slip_hint(
      [&](double scale) { return meets_box(scaled(e, keys, scale), device_low, device_high); },
      [&](double scale) {
        return scaled(e, keys, scale).can_act_within(scene.safety.workspace_min_m, scene.safety.workspace_max_m);
      },
      [&](const char* unit) {
        std::string text;
        for (const char* key : keys) text += (text.empty() ? "" : ", ") + written_in(e, key, unit);
        return text;
      });
}

// A 2-D effect with a gain that still cannot act: its solid beyond the workspace box, or
// (a cage) the workspace wholly inside its free part, with a unit-slip hint where one
// fits. A field acts wherever its reach meets the workspace box (the damper and the
// texture everywhere; a magnet may lie beyond it).
// The 2-D spring's centre: as spring_warning, against the box round the device's workspace.
std::string planar_spring_warning(const PlanarSpring& spring, const nlohmann::json& written, const PlanarScene& scene) {
  Vec2 low_m;
  Vec2 high_m;
  workspace_bounds(scene.device.limits.workspace, &low_m, &high_m);
  const auto inside = [&](double scale) {
    const Vec2 c_m = spring.center_m * scale;
    return c_m[0] >= low_m[0] && c_m[0] <= high_m[0] && c_m[1] >= low_m[1] && c_m[1] <= high_m[1];
  };
  if (!written_without_unit(written, "center") || inside(1.0)) return "";
  return "(spring): center " + point_text(spring.center_m) + " m lies outside the box round the workspace " +
         box_text(low_m, high_m) + ", so the spring pulls the handle toward a place it cannot reach" +
         unit_slip_hint(inside, inside, [&](const char* unit) {
           return std::string("\"center\": ") + length_text(spring.center_m, unit);
         });
}

template <typename Type>
std::string planar_placement_warning(const Type& e, const nlohmann::json& written, const PlanarScene& scene) {
  if constexpr (std::is_same_v<Type, PlanarSpring>) {
    return planar_spring_warning(e, written, scene);
  } else if constexpr (!Type::kUsesProxy) {
    // A field acts wherever its reach meets the workspace box (a magnet beyond it does not).
    if (e.can_act_within(scene.safety.workspace_min_m, scene.safety.workspace_max_m)) return "";
    return std::string("(") + Type::kType + "): its reach lies wholly outside " + planar_workspace_text(scene) +
           ", so the " + Type::kType + " never acts";
  } else {
    if (e.can_act_within(scene.safety.workspace_min_m, scene.safety.workspace_max_m)) return "";
    const std::string workspace = planar_workspace_text(scene);
    const std::string solid = solid_text(e);
    const std::string hint = planar_unit_slip_hint(e, written, scene);
    if (solid.empty()) {
      return std::string("(") + Type::kType + "): " + workspace + " lies wholly inside the " + Type::kType +
             "'s free part (\"solid\": \"outside\"), so the " + Type::kType + " never acts" + hint;
    }
    const char* verb = std::is_same_v<Type, PlanarWall> ? " does not meet " : " lies wholly outside ";
    return std::string("(") + Type::kType + "): " + solid + verb + workspace + ", so the " + Type::kType +
           " never acts" + hint;
  }
}

}  // namespace

std::string inert_effect_warning(const Effect& effect, const nlohmann::json& written, const Scene& scene) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  return effect_warning(effect, -kInfinity, kInfinity, [&](const auto& e) -> std::string {
    using Type = std::decay_t<decltype(e)>;
    if constexpr (std::is_same_v<Type, Wall>) return wall_warning(e, written, scene);
    if constexpr (std::is_same_v<Type, Spring>) return spring_warning(e, written, scene);
    // Any other effect that the workspace keeps from acting (a magnet beyond it).
    if (e.can_act_within(scene.safety.workspace_min_m, scene.safety.workspace_max_m)) return "";
    return std::string("(") + Type::kType + "): its reach lies wholly outside the workspace " +
           interval(scene.safety.workspace_min_m, scene.safety.workspace_max_m) + ", so the " + Type::kType +
           " never acts";
  });
}

std::string inert_effect_warning(const PlanarEffect& effect, const nlohmann::json& written, const PlanarScene& scene) {
  // A box beyond any workspace, finite so that the shapes' tests stay free of inf - inf.
  constexpr double kFar_m = 1e300;
  const Vec2 unbounded_low{{-kFar_m, -kFar_m}};
  const Vec2 unbounded_high{{kFar_m, kFar_m}};
  return effect_warning(effect, unbounded_low, unbounded_high,
                        [&](const auto& e) -> std::string { return planar_placement_warning(e, written, scene); });
}

}  // namespace hapscene
