#pragma once
// Helpers shared by the 2-D effect tests: inputs, vectors, parsing from inline JSON.
#include <string>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/effects/planar/planar_effect_types.hpp"

namespace hapscene::planar_test {

inline Vec2 v2(double x, double y) { return Vec2{{x, y}}; }

inline PlanarInput at(double x_m, double y_m, double vx = 0.0, double vy = 0.0) {
  PlanarInput input;
  input.x_m = v2(x_m, y_m);
  input.v_m_per_s = v2(vx, vy);
  input.dt_s = 0.001;
  return input;
}

// Parses one effect as element 2 of "effects" in env.json.
inline PlanarEffect parse_effect(const std::string& json_text) {
  PlanarEffect effect;
  if (!parse_planar_effect(nlohmann::json::parse(json_text), "/effects/2", "env.json", &effect)) {
    throw InputError("disabled");
  }
  return effect;
}

template <typename T>
T parse_as(const std::string& json_text) {
  return std::get<T>(parse_effect(json_text));
}

// The message of the InputError parsing throws, or "" when it parses.
inline std::string parse_error(const std::string& json_text) {
  try {
    parse_effect(json_text);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace hapscene::planar_test
