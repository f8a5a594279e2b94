// JSON keys of the 2-D effects. Like the 1-D effects (engine/effects/lab_effects.cpp),
// each parse reads every key it accepts, so the caller's finish() refuses the others,
// checks each number against its finite range, and refuses shapes that make no sense
// (a zero normal, min >= max, a polygon that crosses itself) with the place and the reason.
#include "engine/base/json_source.hpp"
#include "engine/base/polygon.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/effects/planar/planar_fields.hpp"
#include "engine/effects/planar/planar_reader.hpp"
#include "engine/effects/planar/planar_shapes.hpp"

namespace hapscene {
namespace {

// A key of a 1-D effect's form ("position" on a wall) in a 2-D effect: says which form a
// 2-D scene expects rather than only "unknown key".
void refuse_1d_key(ObjectReader& reader, std::string_view key, const std::string& message) {
  if (!reader.has(key)) return;
  reader.get(key);
  reader.fail(key, message);
}

}  // namespace

PlanarSpring PlanarSpring::parse(ObjectReader& reader) {
  PlanarSpring spring;
  spring.stiffness_N_per_m = reader.quantity("stiffness", Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m);
  spring.center_m = read_vector_or(reader, "center", Quantity::length_m, Vec2{}, ranges::kPosition_m);
  return spring;
}

PlanarDamper PlanarDamper::parse(ObjectReader& reader) {
  PlanarDamper damper;
  damper.damping_N_s_per_m = reader.quantity("damping", Quantity::damping_N_s_per_m, ranges::kDamping_N_s_per_m);
  return damper;
}

PlanarTexture PlanarTexture::parse(ObjectReader& reader) {
  PlanarTexture texture;
  Texture& bands = texture.bands;
  bands.width_m = reader.quantity("width", Quantity::length_m, ranges::kFieldWidth_m);
  bands.damping_N_s_per_m = reader.quantity("damping", Quantity::damping_N_s_per_m, ranges::kDamping_N_s_per_m);
  bands.spacing_m = reader.quantity_or("spacing", Quantity::length_m, bands.width_m, ranges::kLength_m);
  bands.offset_m = reader.quantity_or("offset", Quantity::length_m, 0.0, ranges::kPosition_m);
  bands.derive_period();
  texture.direction = read_direction(reader, "direction");
  return texture;
}

PlanarWall PlanarWall::parse(ObjectReader& reader) {
  refuse_1d_key(reader, "position",
                "is a key of the 1-D wall: a 2-D wall takes \"point\": [x, y] and \"normal\": [nx, ny]");
  PlanarWall wall;
  wall.point_m = read_vector(reader, "point", Quantity::length_m, ranges::kPosition_m);
  wall.normal = read_direction(reader, "normal");
  wall.stiffness_N_per_m = reader.quantity("stiffness", Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m);
  refuse_1d_key(reader, "solid",
                "is a key of the 1-D wall: a 2-D wall is solid on the side its normal points away from");
  return wall;
}

PlanarBox PlanarBox::parse(ObjectReader& reader) {
  const Vec2 min_m = read_vector(reader, "min", Quantity::length_m, ranges::kPosition_m);
  const Vec2 max_m = read_vector(reader, "max", Quantity::length_m, ranges::kPosition_m);
  for (int axis = 0; axis < 2; ++axis) {
    if (!(min_m[axis] < max_m[axis])) {
      reader.fail("max", std::string("must be above \"min\" in ") + (axis == 0 ? "x" : "y") + ", got min " +
                             format_number(min_m[axis]) + " m and max " + format_number(max_m[axis]) + " m");
    }
  }
  const double stiffness = reader.quantity("stiffness", Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m);
  return make(min_m, max_m, stiffness, read_solid_inside(reader));
}

PlanarCircle PlanarCircle::parse(ObjectReader& reader) {
  PlanarCircle circle;
  circle.center_m = read_vector(reader, "center", Quantity::length_m, ranges::kPosition_m);
  circle.radius_m = reader.quantity("radius", Quantity::length_m, ranges::kRadius_m);
  circle.stiffness_N_per_m = reader.quantity("stiffness", Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m);
  circle.solid_inside = read_solid_inside(reader);
  return circle;
}

PlanarPolygon PlanarPolygon::parse(ObjectReader& reader) {
  const std::vector<Vec2> points = read_points(reader, "points", ranges::kPosition_m, 3, kMaxPolygonPoints);
  const std::string problem = simple_polygon_problem(points);
  if (!problem.empty()) reader.fail("points", problem);
  PlanarPolygon polygon;
  polygon.stiffness_N_per_m = reader.quantity("stiffness", Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m);
  polygon.outline = PolygonOutline(points, read_solid_inside(reader));
  polygon.friction = read_friction(reader);
  return polygon;
}

}  // namespace hapscene
