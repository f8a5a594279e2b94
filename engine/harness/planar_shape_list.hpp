#pragma once
// A planar scene's shapes (walls, boxes, circles, polygons) as geometry for figures and
// scenarios, in the order of the run's proxies (TickStateOf<2>::effect_runs: the bank's
// groups wall, box, circle, polygon, each in the order of the file), so entry i is the
// shape whose proxy is effect_runs[i].
#include <memory>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/effects/planar/polygon_outline.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

enum class PlanarShapeKind { wall, box, circle, polygon };

// "wall", "box", "circle", "polygon": the effects' "type" names.
const char* planar_shape_kind_name(PlanarShapeKind kind) noexcept;

struct PlanarShapeGeometry {
  PlanarShapeKind kind{};
  bool solid_inside{true};              // box, circle, polygon ("outside": a cage)
  Vec2 point_m{};                       // wall: a point on its line
  Vec2 normal{};                        // wall: unit, out of the solid
  Vec2 center_m{};                      // circle
  double radius_m{};                    // circle
  std::vector<Vec2> points_m;           // box: its corners counter-clockwise from min; polygon: its points
  const PolygonOutline* outline{};      // box, polygon: the scene's (valid while the scene lives)
  double stiffness_N_per_m{};           // the effect's stiffness (0 for a declared shape)
  // A shape a script declares (its `shapes`): it has no proxy of its own (the script
  // renders itself), so the run records the handle in its place; its outline, if a box.
  bool declared{};
  std::shared_ptr<const PolygonOutline> owned_outline;

  // How deep p is in the shape's solid: the distance to the boundary, positive in the
  // solid (a wall's half-plane, a solid disc or box or polygon, or outside a cage),
  // negative outside it.
  double depth_m(const Vec2& p_m) const noexcept;

  // The point of the shape's boundary nearest to p (a wall's line, a circle's rim, an
  // outline); the circle's centre goes to (cx + r, cy).
  Vec2 nearest_boundary_m(const Vec2& p_m) const noexcept;
};

std::vector<PlanarShapeGeometry> planar_shape_list(const PlanarScene& scene);

// What validate's scenarios press into, swipe across and release from: the built-in
// shapes (planar_shape_list, so entry i < its size is still the proxy of effect_runs[i]),
// then the boxes and circles the scene's scripts declare in their `shapes` (script by
// script in the file's order, each in its own), marked `declared`. The same as
// planar_shape_list for a scene whose scripts declare none.
std::vector<PlanarShapeGeometry> planar_scenario_shapes(const PlanarScene& scene);

// The index of the shape whose boundary is nearest to p (the first on a tie), or -1 when
// the list is empty.
int nearest_shape_index(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& p_m) noexcept;

}  // namespace hapscene
