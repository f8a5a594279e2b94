#include "engine/cli/new_templates.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/base/object_reader.hpp"

namespace hapscene {
namespace {

// "12.5 mm": a length as a template writes it (rounded to 0.1 mm, enough for a start).
std::string mm_text(double x_m) {
  const double tenths = std::round(x_m * 1e4);
  return format_number(tenths / 10.0 + 0.0) + " mm";
}

nlohmann::ordered_json mm_pair(const Vec2& p_m) { return nlohmann::ordered_json::array({mm_text(p_m[0]), mm_text(p_m[1])}); }

// The built-in effect each environment kind starts with, and what its description says.
struct EffectTemplate {
  nlohmann::ordered_json effect;
  std::string guidance;
};

EffectTemplate effect_template(std::string_view kind, const PlanarPlacement& planar) {
  if (kind == "spring") {
    return {{{"type", "spring"}, {"stiffness", "100 N/m"}, {"center", "0 mm"}},
            "A spring that pulls the handle to its center: F = -stiffness (x - center). Start soft (30 to 100 N/m); "
            "on a Hapkit at 1 kHz keep it below about 800 N/m, the sampled wall's stability bound 2b/T."};
  }
  if (kind == "wall") {
    return {{{"type", "wall"}, {"position", "10 mm"}, {"stiffness", "500 N/m"}, {"solid", "above"}},
            "A wall at position: free motion on one side, a spring of stiffness pushing back on the solid side "
            "(\"above\" or \"below\" the position). 500 N/m is firm on a Hapkit; validate says how stiff it may be."};
  }
  if (kind == "damper") {
    return {{{"type", "damper"}, {"damping", "1 N*s/m"}},
            "A damper: F = -damping v, like moving the handle through honey. A few N*s/m is thick; too much "
            "buzzes, because the velocity is estimated from the sensor."};
  }
  if (kind == "texture") {
    return {{{"type", "texture"}, {"width", "5 mm"}, {"spacing", "5 mm"}, {"damping", "2 N*s/m"}, {"offset", "0 mm"}},
            "A damping-band texture: bands of width, every spacing from offset, that damp the handle (F = -damping v) "
            "while it is inside one. Narrow, closely spaced bands feel like a file; wide ones like sticky patches."};
  }
  const Vec2 half = planar.half_size_m;
  if (kind == "box") {
    const Vec2 low{planar.center_m[0] - half[0], planar.center_m[1] - half[1]};
    const Vec2 high{planar.center_m[0] + half[0], planar.center_m[1] + half[1]};
    return {{{"type", "box"}, {"min", mm_pair(low)}, {"max", mm_pair(high)}, {"stiffness", "200 N/m"}, {"solid", "inside"}},
            "A box from min to max ([x, y]) in the device's workspace: a solid block (\"inside\") or a "
            "cage (\"outside\"), its walls springs of stiffness. validate gives the stiffness the device allows."};
  }
  if (kind == "circle") {
    const double radius_m = std::min(half[0], half[1]);
    return {{{"type", "circle"}, {"center", mm_pair(planar.center_m)}, {"radius", mm_text(radius_m)},
             {"stiffness", "200 N/m"}, {"solid", "inside"}},
            "A circle of radius around center ([x, y]) in the device's workspace: a disc (\"inside\") "
            "or a round cage (\"outside\"), its rim a spring of stiffness."};
  }
  throw std::logic_error("environment_template: no template for \"" + std::string(kind) + "\"");
}

}  // namespace

const std::vector<NewKind>& new_kinds() {
  static const std::vector<NewKind> kinds = {
      {"spring", 1, "a spring (1-DOF environment, NAME.json)"},
      {"wall", 1, "a wall with a solid side (1-DOF environment, NAME.json)"},
      {"damper", 1, "a damper (1-DOF environment, NAME.json)"},
      {"texture", 1, "a damping-band texture (1-DOF environment, NAME.json)"},
      {"script", 1, "a force written in Lua (1-DOF, NAME.lua)"},
      {"box", 2, "a box (2-DOF environment, NAME.json, on --device)"},
      {"circle", 2, "a circle (2-DOF environment, NAME.json, on --device)"},
      {"planar-script", 2, "a 2-D force written in Lua (NAME.lua, and NAME.json that runs it on --device)"},
      {"spec", 0, "a test spec (NAME.test.json) for NAME.json or NAME.lua beside it"},
  };
  return kinds;
}

std::string environment_template(std::string_view kind, const std::string& name, const PlanarPlacement& planar) {
  nlohmann::ordered_json document;
  document["name"] = name;
  if (kind == "planar-script") {
    document["description"] = "Runs " + name + ".lua on " + planar.device +
                              ". The force is in the script; its params can be set here too, e.g. "
                              "\"params\": {\"stiffness\": \"150 N/m\"} in the effect.";
    document["device"] = planar.device;
    document["effects"] = nlohmann::ordered_json::array({{{"type", "script"}, {"file", name + ".lua"}}});
    return document.dump(2) + "\n";
  }
  const EffectTemplate effect = effect_template(kind, planar);
  document["description"] = effect.guidance + " Check it with `hapscene validate " + name +
                            ".json`, then feel it with `hapscene run " + name + ".json`.";
  if (!planar.device.empty() && (kind == "box" || kind == "circle")) document["device"] = planar.device;
  document["effects"] = nlohmann::ordered_json::array({effect.effect});
  return document.dump(2) + "\n";
}

std::string script_template(int axes, const std::string& name, const PlanarPlacement& planar) {
  if (axes == 1) {
    return "-- " + name +
           ": a force written in Lua, called every tick (1000 times a second).\n"
           "-- force(s) gets the handle's state: s.x (m), and s.v (m/s) and s.t (s) when `needs` asks\n"
           "-- for them; it returns the force in N (positive pushes towards +x). It must be quick\n"
           "-- and may not print or read files: the sandbox refuses what a tick cannot afford.\n"
           "-- This one is a spring with a dead band: nothing within +/-band of center, then a\n"
           "-- pull back of stiffness beyond it. Change the formula; keep it continuous (a jump in\n"
           "-- force is felt as a knock, and validate reports it).\n"
           "-- Check it:  hapscene validate " + name + ".lua     Feel it:  hapscene run " + name +
           ".lua\n"
           "params = {\n"
           "  stiffness = \"100 N/m\",  -- K (values with units are read into SI: N/m here)\n"
           "  center = \"0 mm\",        -- x0\n"
           "  band = \"5 mm\",          -- half the width of the dead band\n"
           "}\n"
           "needs = { velocity = false, time = false }  -- set true to get s.v and s.t\n"
           "\n"
           "local K, x0, band = params.stiffness, params.center, params.band\n"
           "\n"
           "function force(s)\n"
           "  local d = s.x - x0\n"
           "  if d > band then return -K * (d - band) end\n"
           "  if d < -band then return -K * (d + band) end\n"
           "  return 0\n"
           "end\n";
  }
  return "-- " + name + ": a 2-D force written in Lua, called every tick (1000 times a second).\n"
         "-- force(s) gets the handle's state in the device's plane: s.x, s.y (m), and s.vx, s.vy\n"
         "-- (m/s) and s.t (s) when `needs` asks for them; it returns two forces in N, (fx, fy).\n"
         "-- " + name + ".json runs it on " + planar.device + ".\n"
         "-- This one is a tether: free within radius of a point, then pulled back towards it\n"
         "-- by a spring of stiffness, never harder than max_force. Change the formula; keep it\n"
         "-- continuous (a jump in force is felt as a knock).\n"
         "-- Check it:  hapscene validate " + name + ".json     Feel it:  hapscene run " + name + ".json\n"
         "params = {\n"
         "  center_x = \"" + mm_text(planar.center_m[0]) + "\", center_y = \"" + mm_text(planar.center_m[1]) +
         "\",  -- the point\n"
         "  radius = \"" + mm_text(std::min(planar.half_size_m[0], planar.half_size_m[1])) +
         "\",  -- free within it\n"
         "  stiffness = \"50 N/m\",   -- K, beyond the radius\n"
         "  max_force = \"1 N\",      -- the pull's ceiling\n"
         "}\n"
         "needs = { velocity = false, time = false }\n"
         "\n"
         "local cx, cy, R = params.center_x, params.center_y, params.radius\n"
         "local K, Fmax = params.stiffness, params.max_force\n"
         "local sqrt, min = math.sqrt, math.min\n"
         "\n"
         "function force(s)\n"
         "  local dx, dy = s.x - cx, s.y - cy\n"
         "  local r = sqrt(dx * dx + dy * dy)\n"
         "  if r <= R then return 0, 0 end\n"
         "  local pull = min(K * (r - R), Fmax) / r\n"
         "  return -pull * dx, -pull * dy\n"
         "end\n";
}

std::string spec_template(const std::string& environment_file, int axes) {
  nlohmann::ordered_json document;
  document["environment"] = environment_file;
  const std::string force_example = axes == 1 ? "{\"x\": \"15 mm\", \"force\": \"-2.5 N\"}"
                                              : "{\"at\": [\"-10 mm\", \"120 mm\"], \"force\": [\"0 N\", \"1 N\"]}";
  document["description"] =
      "What " + environment_file +
      " should feel like, checked by `hapscene test`. For now it asks only that every validate scenario "
      "passes; add what your formula says, for example \"forces\": [" + force_example +
      "], \"never_exceeds\": \"3 N\", and limits per scenario (the test spec reference lists every key).";
  document["passes_validate"] = true;
  return document.dump(2) + "\n";
}

}  // namespace hapscene
