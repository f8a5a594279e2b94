// The parts of the 2-D shapes' declarations (engine/effects/planar/planar_shapes.hpp) that
// are more than a key of a declared form: a box's corners in order, a polygon's points
// (a simple outline) and its friction. Each refuses what makes no sense with the place and
// the reason.
#include <string>

#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/base/polygon.hpp"
#include "engine/effects/planar/planar_shapes.hpp"
#include "engine/effects/vector_reader.hpp"

namespace hapscene {

void PlanarBox::check_max_above_min(ObjectReader& reader, const PlanarBox& box) {
  for (int axis = 0; axis < kAxes; ++axis) {
    if (!(box.min_m[axis] < box.max_m[axis])) {
      reader.fail("max", std::string("must be above \"min\" in ") + kAxisNames[axis] + ", got min " +
                             format_number(box.min_m[axis]) + " m and max " + format_number(box.max_m[axis]) + " m");
    }
  }
}

void PlanarPolygon::read_points(ObjectReader& reader, PlanarPolygon& polygon) {
  static constexpr EffectKey points = *find_key(declaration_of<PlanarPolygon>(), "points");
  polygon.points_m = hapscene::read_points(reader, points.name, points.range, static_cast<std::size_t>(points.min_items),
                                           static_cast<std::size_t>(points.max_items));
  const std::string problem = simple_polygon_problem(polygon.points_m);
  if (!problem.empty()) reader.fail("points", problem);
}

void PlanarPolygon::read_friction_key(ObjectReader& reader, PlanarPolygon& polygon) {
  polygon.friction = read_friction(reader);
}

}  // namespace hapscene
