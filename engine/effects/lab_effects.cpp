// JSON keys of the four Hapkit lab effects. Each parse reads every key the effect
// accepts (so unknown keys can be refused with a suggestion) and checks it against its
// finite range (engine/base/physical_ranges.hpp).
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/effects/damper.hpp"
#include "engine/effects/spring.hpp"
#include "engine/effects/texture.hpp"
#include "engine/effects/wall.hpp"

namespace hapscene {

Spring Spring::parse(ObjectReader& reader) {
  Spring spring;
  spring.stiffness_N_per_m =
      reader.quantity("stiffness", Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m);
  spring.center_m = reader.quantity_or("center", Quantity::length_m, 0.0, ranges::kPosition_m);
  return spring;
}

Wall Wall::parse(ObjectReader& reader) {
  Wall wall;
  wall.position_m = reader.quantity("position", Quantity::length_m, ranges::kPosition_m);
  wall.stiffness_N_per_m =
      reader.quantity("stiffness", Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m);
  wall.solid_above = reader.choice("solid", {"above", "below"}) == "above";
  return wall;
}

Damper Damper::parse(ObjectReader& reader) {
  Damper damper;
  damper.damping_N_s_per_m =
      reader.quantity("damping", Quantity::damping_N_s_per_m, ranges::kDamping_N_s_per_m);
  return damper;
}

Texture Texture::parse(ObjectReader& reader) {
  Texture texture;
  texture.width_m = reader.quantity("width", Quantity::length_m, ranges::kFieldWidth_m);
  texture.damping_N_s_per_m =
      reader.quantity("damping", Quantity::damping_N_s_per_m, ranges::kDamping_N_s_per_m);
  texture.spacing_m =
      reader.quantity_or("spacing", Quantity::length_m, texture.width_m, ranges::kLength_m);
  texture.offset_m = reader.quantity_or("offset", Quantity::length_m, 0.0, ranges::kPosition_m);
  texture.derive_period();
  if (const nlohmann::json* mirror = reader.get("mirror")) {
    if (!mirror->is_boolean()) reader.fail("mirror", "expected a boolean, got " + json_type_name(*mirror));
    texture.mirror = mirror->get<bool>();
  }
  return texture;
}

}  // namespace hapscene
