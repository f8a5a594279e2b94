#include "engine/load/effect_warnings.hpp"

#include <limits>
#include <utility>

#include "engine/base/object_reader.hpp"
#include "engine/base/units.hpp"

namespace hapscene {
namespace {

// The key and unit of a built-in effect's gain, for "(spring): stiffness 0 N/m".
struct Gain {
  const char* key;
  const char* unit;
};
Gain gain_of(const Spring&) { return {"stiffness", "N/m"}; }
Gain gain_of(const Wall&) { return {"stiffness", "N/m"}; }
Gain gain_of(const Damper&) { return {"damping", "N*s/m"}; }
Gain gain_of(const Texture&) { return {"damping", "N*s/m"}; }

std::string interval(double low_m, double high_m) {
  return "[" + format_number(low_m) + ", " + format_number(high_m) + "] m";
}

// Whether a length was written without a unit (a number, or a string such as "20"): then
// it is metres, and 20 meant as 20 mm is 20 m.
bool written_without_unit(const nlohmann::json& written, const char* key) {
  const auto value = written.find(key);
  if (value == written.end()) return false;
  if (value->is_number()) return true;
  if (!value->is_string()) return false;
  const QuantityParse parsed = parse_quantity(value->get<std::string>());
  return parsed.ok && parsed.quantity == Quantity::dimensionless;
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
  const auto inside_device = [&](double x_m) { return x_m > device.workspace_min_m && x_m < device.workspace_max_m; };
  if (inside_device(wall.position_m) || !written_without_unit(written, "position")) return message;
  for (const auto& [unit, scale] : {std::pair{"mm", 1e-3}, std::pair{"cm", 1e-2}}) {
    const double x_m = wall.position_m * scale;
    if (!inside_device(x_m)) continue;
    message += "; did you mean \"" + format_number(wall.position_m) + " " + unit + "\"?";
    Wall moved = wall;
    moved.position_m = x_m;
    if (!moved.can_act_within(low_m, high_m)) message += " (even there it would not act within /safety/workspace)";
    break;
  }
  return message;
}

}  // namespace

std::string inert_effect_warning(const Effect& effect, const nlohmann::json& written, const Scene& scene) {
  return std::visit(
      [&](const auto& e) -> std::string {
        using Type = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<Type, ScriptEffect>) {
          return "";  // a script's force is known only by running it
        } else {
          // A zero gain: the effect does nothing anywhere.
          constexpr double kInfinity = std::numeric_limits<double>::infinity();
          if (!e.can_act_within(-kInfinity, kInfinity)) {
            const Gain gain = gain_of(e);
            return std::string("(") + Type::kType + "): " + gain.key + " 0 " + gain.unit + ", so the " + Type::kType +
                   " never acts (\"enabled\": false leaves an effect out without a warning)";
          }
          if constexpr (std::is_same_v<Type, Wall>) return wall_warning(e, written, scene);
          return "";
        }
      },
      effect);
}

}  // namespace hapscene
