#include "engine/bench/lua_equivalent.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

// Shortest exact decimal text of a number, for generated Lua source.
std::string exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

std::optional<Scene> lua_equivalent(const Scene& scene, const std::string& scripts_dir) {
  if (scene.effects.size() != 1) return std::nullopt;
  nlohmann::json effect = {{"type", "script"}};
  const Effect& e = scene.effects[0];
  if (const auto* spring = std::get_if<Spring>(&e)) {
    effect["file"] = scripts_dir + "/spring.lua";
    effect["params"] = {{"stiffness", spring->stiffness_N_per_m}, {"center", spring->center_m}};
  } else if (const auto* mirrored = std::get_if<Texture>(&e); mirrored && mirrored->mirror) {
    // The lab's mirrored texture: fields where |x - x0| mod p < w (scripts/texture.lua has
    // no mirror).
    effect["source"] = "needs = { time = false }\n"
                       "local B, w, x0, p = " + exact(mirrored->damping_N_s_per_m) + ", " + exact(mirrored->width_m) +
                       ", " + exact(mirrored->offset_m) + ", " + exact(mirrored->period_m) + "\n"
                       "function force(s)\n"
                       "  if math.abs(s.x - x0) % p < w then return -B * s.v end\n"
                       "  return 0\n"
                       "end\n";
  } else if (const auto* texture = std::get_if<Texture>(&e)) {
    effect["file"] = scripts_dir + "/texture.lua";
    effect["params"] = {{"damping", texture->damping_N_s_per_m}, {"width", texture->width_m},
                        {"gap", texture->spacing_m}, {"origin", texture->offset_m}};
  } else if (const auto* wall = std::get_if<Wall>(&e)) {
    // The lab wall: F = -K (x - xw) inside the solid side, else 0.
    effect["source"] = "needs = { velocity = false, time = false }\n"
                       "local K, xw = " + exact(wall->stiffness_N_per_m) + ", " + exact(wall->position_m) + "\n"
                       "function force(s)\n"
                       "  if s.x " + std::string(wall->solid_above ? ">" : "<") + " xw then return -K * (s.x - xw) end\n"
                       "  return 0\n"
                       "end\n";
  } else if (const auto* damper = std::get_if<Damper>(&e)) {
    // The lab damper: F = -B v.
    effect["source"] = "needs = { time = false }\n"
                       "local B = " + exact(damper->damping_N_s_per_m) + "\n"
                       "function force(s) return -B * s.v end\n";
  } else {
    return std::nullopt;
  }
  nlohmann::json environment = {{"name", scene.name + " (Lua)"}, {"rate_hz", scene.rate_hz},
                                {"effects", nlohmann::json::array({effect})}};
  // Same device, safety and velocity estimator: only the effects stage differs.
  Scene lua = load_environment_text(environment.dump(), scene.name + ".lua.json", ".");
  lua.device = scene.device;
  lua.device_model = scene.device_model;
  lua.safety = scene.safety;
  lua.velocity = scene.velocity;
  return lua;
}

}  // namespace hapscene
