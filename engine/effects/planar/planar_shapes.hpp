#pragma once
// The 2-D shapes: wall (a half-plane), box, circle and polygon. Each renders a god-object
// proxy: F = K (proxy - x), component by component, fx = K (proxy_x - x), fy = K (proxy_y - y).
//
// Two evaluations each:
// - force_N(input, state): closed loop, the run's tick. `state` is the shape's proxy for
//   this run (value-initialised at the start of the run, owned by the caller); no
//   allocation. A run that starts with the handle in the solid gives no force until the
//   handle has left the solid (the proxy starts at the handle and follows it, as in
//   CHAI3D). Non-finite input gives zero force and leaves the state alone.
// - open_loop_force_N(input) / open_loop_proxy_m(x): no history (probe, field scans, test
//   specs). The proxy is the nearest point of the solid's boundary to x when x is in the
//   solid, else x: where the closed-loop proxy rests when the handle came in from outside
//   the shortest way. The formulas are written out per shape below, in the order they are
//   computed, so a script can reproduce them to the bit.
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/effects/planar/polygon_outline.hpp"
#include "engine/effects/planar/proxy_state.hpp"

namespace hapscene {

// Most points a polygon may have: bounds the load's work (the grid and the crossing
// check) and the memory of one effect.
inline constexpr int kMaxPolygonPoints = 10000;

// F = K (proxy - x) per component, the shapes' force law.
inline Vec2 proxy_force_N(double stiffness_N_per_m, const Vec2& proxy_m, const Vec2& x_m) noexcept {
  return Vec2{{stiffness_N_per_m * (proxy_m[0] - x_m[0]), stiffness_N_per_m * (proxy_m[1] - x_m[1])}};
}

// A half-plane wall through `point` with unit normal n pointing out of the solid.
// Open loop: d = (point_x - x) nx + (point_y - y) ny; when d > 0 (in the solid)
// F = (K d) n, i.e. fx = K * d * nx, fy = K * d * ny, and the proxy is x + d n (the foot
// of the perpendicular on the wall's line); else F = 0 and the proxy is x. The closed loop
// gives the same force once the handle has been outside the solid: the free side is a
// half-plane, so the proxy reaches the same foot whatever the path.
struct PlanarWall {
  static constexpr const char* kType = "wall";
  static constexpr Needs kNeeds{};
  static constexpr bool kUsesProxy = true;
  static constexpr int kAxes = 2;
  static constexpr const char* kDescription = "a half-plane wall";

  Vec2 point_m{};
  Vec2 normal{};  // unit: the normal as written divided by sqrt(nx nx + ny ny)
  double stiffness_N_per_m{};

  static constexpr auto keys() {
    return std::array{
        KeyOf<PlanarWall>{effect_keys::refused("position", "is a key of the 1-D wall: a 2-D wall takes \"point\": [x, y] and "
                                                           "\"normal\": [nx, ny]")},
        KeyOf<PlanarWall>{effect_keys::place("point", "point_m", KeyForm::vector, "a point of the wall's line"),
                          [](PlanarWall& e) { return e.point_m.value; }},
        KeyOf<PlanarWall>{effect_keys::direction("normal", "points out of the solid side"),
                          [](PlanarWall& e) { return e.normal.value; }},
        KeyOf<PlanarWall>{effect_keys::stiffness(), [](PlanarWall& e) { return &e.stiffness_N_per_m; }},
        KeyOf<PlanarWall>{effect_keys::refused("solid", "is a key of the 1-D wall: a 2-D wall is solid on the side its "
                                                        "normal points away from")},
    };
  }

  double depth_m(const Vec2& x_m) const noexcept {
    return (point_m[0] - x_m[0]) * normal[0] + (point_m[1] - x_m[1]) * normal[1];
  }
  Vec2 open_loop_proxy_m(const Vec2& x_m) const noexcept {
    const double d = depth_m(x_m);
    if (!(d > 0.0)) return x_m;
    return Vec2{{x_m[0] + d * normal[0], x_m[1] + d * normal[1]}};
  }
  Vec2 open_loop_force_N(const PlanarInput& in) const noexcept {
    const double d = depth_m(in.x_m);
    if (!(d > 0.0)) return Vec2{};
    return Vec2{{stiffness_N_per_m * d * normal[0], stiffness_N_per_m * d * normal[1]}};
  }
  Vec2 force_N(const PlanarInput& in, PlanarProxyState& state) const noexcept;
  bool can_act_within(const Vec2& min_m, const Vec2& max_m) const noexcept;
};

// An axis-aligned box [min, max]. Open loop, solid "inside": when min_x < x < max_x and
// min_y < y < max_y, the distances to the sides left = x - min_x, right = max_x - x,
// bottom = y - min_y, top = max_y - y are compared and the proxy goes to the nearest side
// (ties: the first in that order): (min_x, y), (max_x, y), (x, min_y) or (x, max_y);
// elsewhere the proxy is x. Solid "outside" (a cage): the proxy is
// (clamp(x, min_x, max_x), clamp(y, min_y, max_y)), which is x inside the box.
// Closed loop: the outline's proxy (engine/effects/planar/polygon_outline.hpp) on the
// edges bottom, right, top, left. Pressed in from outside along a side's normal it rests
// on the open loop's proxy to rounding (the outline computes the foot as corner + distance
// along the side: within 1e-15 m of it, tests/effects/planar_shapes_test.cpp); the wall's
// and the circle's closed loops give the open loop's numbers exactly.
struct PlanarBox {
  static constexpr const char* kType = "box";
  static constexpr Needs kNeeds{};
  static constexpr bool kUsesProxy = true;
  static constexpr int kAxes = 2;
  static constexpr const char* kDescription = "an axis-aligned box";

  Vec2 min_m{};
  Vec2 max_m{};
  double stiffness_N_per_m{};
  bool solid_inside{true};
  PolygonOutline outline;  // built by make()

  static constexpr auto keys() {
    return std::array{
        KeyOf<PlanarBox>{effect_keys::place("min", "min_m", KeyForm::vector, "the lowest corner"),
                         [](PlanarBox& e) { return e.min_m.value; }},
        KeyOf<PlanarBox>{effect_keys::place("max", "max_m", KeyForm::vector, "the highest corner, above min on every axis"),
                         [](PlanarBox& e) { return e.max_m.value; }, nullptr, nullptr, &check_max_above_min},
        KeyOf<PlanarBox>{effect_keys::stiffness(), [](PlanarBox& e) { return &e.stiffness_N_per_m; }},
        KeyOf<PlanarBox>{effect_keys::solid("inside", "outside", "solid_inside"), nullptr,
                         [](PlanarBox& e) { return &e.solid_inside; }},
    };
  }
  static void check_max_above_min(ObjectReader& reader, const PlanarBox& box);
  static void finish_parse(ObjectReader&, PlanarBox& box) {
    box = make(box.min_m, box.max_m, box.stiffness_N_per_m, box.solid_inside);
  }
  // A box with its outline (min < max in both axes).
  static PlanarBox make(const Vec2& min_m, const Vec2& max_m, double stiffness_N_per_m, bool solid_inside);

  Vec2 open_loop_proxy_m(const Vec2& x_m) const noexcept;
  Vec2 open_loop_force_N(const PlanarInput& in) const noexcept {
    return proxy_force_N(stiffness_N_per_m, open_loop_proxy_m(in.x_m), in.x_m);
  }
  // (Inlined into the tick with the outline's fast paths.)
  [[gnu::always_inline]] Vec2 force_N(const PlanarInput& in, PlanarProxyState& state) const noexcept {
    if (!all_finite(in.x_m)) return Vec2{};
    outline.step_proxy(in.x_m, FrictionCoefficients{}, state);
    return proxy_force_N(stiffness_N_per_m, state.proxy_m, in.x_m);
  }
  bool can_act_within(const Vec2& min_m, const Vec2& max_m) const noexcept;
};

// A circle of centre c and radius r. Open loop: dx = x - cx, dy = y - cy,
// distance = sqrt(dx * dx + dy * dy); the handle is in the solid when distance < r
// ("inside") or distance > r ("outside", a cage); there the proxy is
// (cx + dx * (r / distance), cy + dy * (r / distance)), and at the very centre (distance 0,
// "inside" only) (cx + r, cy); elsewhere the proxy is x.
// Closed loop: a free proxy moves straight toward the handle and stops where its path
// meets the circle (a disc crossed within one tick included); on the circle it slides to
// the open loop's nearest point when that lies less than a quarter turn round from it,
// else it holds (at the centre too), so a handle that went past the middle of a disc
// is pushed back the way it came, never on through. A disc's proxy leaves the circle for
// a handle out of the disc that a slide of less than a quarter turn brings into view,
// and holds for one behind the disc (which crossed it). So the closed loop equals the open
// loop except at the start (no force until the handle has left a solid it started in)
// and for a handle past the middle of a disc, or behind it.
struct PlanarCircle {
  static constexpr const char* kType = "circle";
  static constexpr Needs kNeeds{};
  static constexpr bool kUsesProxy = true;
  static constexpr int kAxes = 2;
  static constexpr const char* kDescription = "a circle";

  Vec2 center_m{};
  double radius_m{};
  double stiffness_N_per_m{};
  bool solid_inside{true};

  static constexpr auto keys() {
    return std::array{
        KeyOf<PlanarCircle>{effect_keys::place("center", "center_m", KeyForm::vector),
                            [](PlanarCircle& e) { return e.center_m.value; }},
        KeyOf<PlanarCircle>{key("radius", KeyForm::number, Quantity::length_m, ranges::kRadius_m)
                                .needed().slides().as("radius_m"),
                            [](PlanarCircle& e) { return &e.radius_m; }},
        KeyOf<PlanarCircle>{effect_keys::stiffness(), [](PlanarCircle& e) { return &e.stiffness_N_per_m; }},
        KeyOf<PlanarCircle>{effect_keys::solid("inside", "outside", "solid_inside"), nullptr,
                            [](PlanarCircle& e) { return &e.solid_inside; }},
    };
  }

  Vec2 open_loop_proxy_m(const Vec2& x_m) const noexcept;
  Vec2 open_loop_force_N(const PlanarInput& in) const noexcept {
    return proxy_force_N(stiffness_N_per_m, open_loop_proxy_m(in.x_m), in.x_m);
  }
  Vec2 force_N(const PlanarInput& in, PlanarProxyState& state) const noexcept;
  bool can_act_within(const Vec2& min_m, const Vec2& max_m) const noexcept;
};

// A polygon (at least 3 points, simple, with an area), solid inside or outside, with
// optional Coulomb friction on its edges (closed loop only: the open loop has no history
// and puts the proxy at the nearest point of the outline, as without friction).
struct PlanarPolygon {
  static constexpr const char* kType = "polygon";
  static constexpr Needs kNeeds{};
  static constexpr bool kUsesProxy = true;
  static constexpr int kAxes = 2;
  static constexpr const char* kDescription = "a simple polygon (3 to 10000 points)";

  PolygonOutline outline;  // built by finish_parse
  double stiffness_N_per_m{};
  FrictionCoefficients friction;
  std::vector<Vec2> points_m;  // as written
  bool solid_inside{true};

  static constexpr auto keys() {
    return std::array{
        KeyOf<PlanarPolygon>{key("points", KeyForm::points, Quantity::length_m, ranges::kPosition_m)
                                 .needed().items(3, kMaxPolygonPoints).says("the corners of a simple outline, in order"),
                             nullptr, nullptr, &read_points},
        KeyOf<PlanarPolygon>{effect_keys::stiffness(), [](PlanarPolygon& e) { return &e.stiffness_N_per_m; }},
        KeyOf<PlanarPolygon>{effect_keys::solid("inside", "outside", "solid_inside"), nullptr,
                             [](PlanarPolygon& e) { return &e.solid_inside; }},
        KeyOf<PlanarPolygon>{key("friction", KeyForm::friction, Quantity::dimensionless, ranges::kFrictionCoefficient)
                                 .says("Coulomb friction on the edges, dynamic at most static"),
                             nullptr, nullptr, &read_friction_key},
    };
  }
  static void read_points(ObjectReader& reader, PlanarPolygon& polygon);
  static void read_friction_key(ObjectReader& reader, PlanarPolygon& polygon);
  static void finish_parse(ObjectReader&, PlanarPolygon& polygon) {
    polygon.outline = PolygonOutline(polygon.points_m, polygon.solid_inside);
  }

  Vec2 open_loop_proxy_m(const Vec2& x_m) const noexcept { return outline.open_loop_proxy(x_m); }
  Vec2 open_loop_force_N(const PlanarInput& in) const noexcept {
    return proxy_force_N(stiffness_N_per_m, open_loop_proxy_m(in.x_m), in.x_m);
  }
  // (Inlined into the tick with the outline's fast paths.)
  [[gnu::always_inline]] Vec2 force_N(const PlanarInput& in, PlanarProxyState& state) const noexcept {
    if (!all_finite(in.x_m)) return Vec2{};
    outline.step_proxy(in.x_m, friction, state);
    return proxy_force_N(stiffness_N_per_m, state.proxy_m, in.x_m);
  }
  // Solid inside: some of the polygon meets the box; a cage: some of the box lies outside
  // the polygon. (An outline touching the box counts as meeting it.)
  bool can_act_within(const Vec2& min_m, const Vec2& max_m) const noexcept;
};

}  // namespace hapscene
