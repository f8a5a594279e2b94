// The 2-D wall, box and circle: open-loop formulas (inside, outside, on edges, corners),
// closed-loop proxies (approach, thin boxes swept fast, cage corners, a run that starts
// in the solid) and the agreement of the two for an approach along the normal.
#include <doctest/doctest.h>

#include <cmath>

#include "tests/effects/planar_test_support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;
using namespace hapscene::planar_test;
using hapscene::planar_test::at;  // before a neighbour's at() in its unity batch

namespace {

// Runs a shape's closed loop through `path` from a fresh state; returns the last force.
template <typename Shape>
Vec2 run(const Shape& shape, PlanarProxyState& state, std::initializer_list<Vec2> path) {
  Vec2 force{};
  for (const Vec2& x : path) {
    PlanarInput input;
    input.x_m = x;
    force = shape.force_N(input, state);
  }
  return force;
}

bool near(const Vec2& a, const Vec2& b, double tolerance = 1e-15) {
  return std::fabs(a[0] - b[0]) <= tolerance && std::fabs(a[1] - b[1]) <= tolerance;
}

}  // namespace

TEST_CASE("planar wall: F = K d n with d = (point - x) . n when d > 0") {
  const PlanarWall wall = parse_as<PlanarWall>(
      R"({"type": "wall", "point": ["0 mm", "10 mm"], "normal": [0, -2], "stiffness": "500 N/m"})");
  CHECK(wall.normal == v2(0.0, -1.0));
  CHECK(wall.open_loop_force_N(at(0.0, 0.0)) == v2(0.0, 0.0));     // free side
  CHECK(wall.open_loop_force_N(at(0.05, 0.01)) == v2(0.0, 0.0));   // on the line
  CHECK(wall.open_loop_force_N(at(0.05, 0.012)) == v2(0.0, 500.0 * ((0.01 - 0.012) * -1.0) * -1.0));
  CHECK(wall.open_loop_force_N(at(0.05, 0.012))[1] < 0.0);          // pushes back down
  CHECK(wall.open_loop_proxy_m(v2(0.05, 0.012)) == v2(0.05, 0.01));
  CHECK(wall.open_loop_proxy_m(v2(0.05, 0.0)) == v2(0.05, 0.0));

  // A slanted wall: the force is along the normal, as deep as the handle is.
  const PlanarWall slanted = parse_as<PlanarWall>(
      R"({"type": "wall", "point": [0, 0], "normal": [1, 1], "stiffness": 1000})");
  const Vec2 f = slanted.open_loop_force_N(at(-0.001, -0.002));
  const double d = (0.0 + 0.001) * slanted.normal[0] + (0.0 + 0.002) * slanted.normal[1];
  CHECK(f == v2(1000.0 * d * slanted.normal[0], 1000.0 * d * slanted.normal[1]));
  CHECK(std::fabs(norm(f) - 1000.0 * 0.003 / std::sqrt(2.0)) < 1e-12);
}

TEST_CASE("planar wall: the closed loop equals the open loop once the handle came from outside") {
  const PlanarWall wall{.point_m = v2(0.0, 0.01), .normal = v2(0.0, -1.0), .stiffness_N_per_m = 500.0};
  PlanarProxyState state;
  CHECK(run(wall, state, {v2(0.0, 0.0)}) == v2(0.0, 0.0));
  for (const Vec2 x : {v2(0.0, 0.011), v2(0.02, 0.013), v2(-0.03, 0.012)}) {
    PlanarInput input;
    input.x_m = x;
    CHECK(wall.force_N(input, state) == wall.open_loop_force_N(input));
    CHECK(state.proxy_m == wall.open_loop_proxy_m(x));
    CHECK(state.contact == ProxyContact::surface);
  }
  CHECK(run(wall, state, {v2(0.0, 0.0)}) == v2(0.0, 0.0));
  CHECK(state.contact == ProxyContact::none);
}

TEST_CASE("planar wall: a run that starts in the solid gives no force until the handle has left it") {
  const PlanarWall wall{.point_m = v2(0.0, 0.01), .normal = v2(0.0, -1.0), .stiffness_N_per_m = 500.0};
  PlanarProxyState state;
  CHECK(run(wall, state, {v2(0.0, 0.015), v2(0.0, 0.02), v2(0.0, 0.012)}) == v2(0.0, 0.0));
  CHECK(state.passive);
  CHECK(run(wall, state, {v2(0.0, 0.005)}) == v2(0.0, 0.0));  // out
  CHECK_FALSE(state.passive);
  CHECK(run(wall, state, {v2(0.0, 0.012)})[1] < 0.0);  // back in: pushed out
}

TEST_CASE("planar wall: non-finite input gives no force and keeps the state") {
  const PlanarWall wall{.point_m = v2(0.0, 0.01), .normal = v2(0.0, -1.0), .stiffness_N_per_m = 500.0};
  PlanarProxyState state;
  run(wall, state, {v2(0.0, 0.0), v2(0.0, 0.012)});
  const PlanarProxyState before = state;
  CHECK(run(wall, state, {v2(NAN, 0.0)}) == v2(0.0, 0.0));
  CHECK(state.proxy_m == before.proxy_m);
}

TEST_CASE("planar box, solid inside: open loop pushes to the nearest side") {
  const PlanarBox box = PlanarBox::make(v2(-0.02, 0.10), v2(0.02, 0.14), 400.0, true);
  // Outside and on the edges: no force.
  CHECK(box.open_loop_force_N(at(0.0, 0.09)) == v2(0.0, 0.0));
  CHECK(box.open_loop_force_N(at(-0.02, 0.12)) == v2(0.0, 0.0));
  CHECK(box.open_loop_force_N(at(0.02, 0.14)) == v2(0.0, 0.0));  // a corner
  CHECK(box.open_loop_force_N(at(0.03, 0.12)) == v2(0.0, 0.0));
  // Near each side: towards it.
  CHECK(box.open_loop_proxy_m(v2(-0.019, 0.12)) == v2(-0.02, 0.12));
  CHECK(box.open_loop_proxy_m(v2(0.018, 0.121)) == v2(0.02, 0.121));
  CHECK(box.open_loop_proxy_m(v2(0.001, 0.101)) == v2(0.001, 0.10));
  CHECK(box.open_loop_proxy_m(v2(0.001, 0.139)) == v2(0.001, 0.14));
  CHECK(box.open_loop_force_N(at(-0.019, 0.12)) == v2(400.0 * (-0.02 - -0.019), 0.0));
  // Near a corner, inside: the nearer of the two sides.
  CHECK(box.open_loop_proxy_m(v2(0.019, 0.1385)) == v2(0.02, 0.1385));
  CHECK(box.open_loop_proxy_m(v2(0.0185, 0.139)) == v2(0.0185, 0.14));
  // Ties go to the first side in the order left, right, bottom, top (distances computed
  // as written: 0.12 - 0.10 is not 0.14 - 0.12 in binary, so ties are checked on a unit box).
  const PlanarBox unit = PlanarBox::make(v2(-1.0, -1.0), v2(1.0, 1.0), 1.0, true);
  CHECK(unit.open_loop_proxy_m(v2(0.0, 0.0)) == v2(-1.0, 0.0));
  CHECK(unit.open_loop_proxy_m(v2(0.5, 0.5)) == v2(1.0, 0.5));
  CHECK(unit.open_loop_proxy_m(v2(-0.5, -0.5)) == v2(-1.0, -0.5));
  CHECK(unit.open_loop_proxy_m(v2(0.25, 0.5)) == v2(0.25, 1.0));
}

TEST_CASE("planar box, solid outside (a cage): open loop clamps into the box, corners hold") {
  const PlanarBox cage = PlanarBox::make(v2(-0.02, 0.10), v2(0.02, 0.14), 400.0, false);
  CHECK(cage.open_loop_force_N(at(0.0, 0.12)) == v2(0.0, 0.0));
  CHECK(cage.open_loop_force_N(at(0.02, 0.12)) == v2(0.0, 0.0));
  CHECK(cage.open_loop_proxy_m(v2(0.025, 0.12)) == v2(0.02, 0.12));
  CHECK(cage.open_loop_proxy_m(v2(0.025, 0.15)) == v2(0.02, 0.14));  // beyond a corner: the corner
  CHECK(cage.open_loop_force_N(at(0.025, 0.15)) == v2(400.0 * (0.02 - 0.025), 400.0 * (0.14 - 0.15)));
}

TEST_CASE("planar box: closed loop agrees with open loop for an approach along each normal") {
  for (const bool solid_inside : {true, false}) {
    const PlanarBox box = PlanarBox::make(v2(-0.02, 0.10), v2(0.02, 0.14), 400.0, solid_inside);
    const double s = solid_inside ? 1.0 : -1.0;  // into the solid
    struct Approach {
      Vec2 start, step;
    };
    // From 5 mm out of each side's middle, 0.5 mm a tick along the inward (or, for the cage, outward) normal.
    const Approach approaches[] = {{v2(-0.02 - s * 0.005, 0.123), v2(s * 0.0005, 0.0)},
                                   {v2(0.02 + s * 0.005, 0.117), v2(-s * 0.0005, 0.0)},
                                   {v2(0.003, 0.10 - s * 0.005), v2(0.0, s * 0.0005)},
                                   {v2(-0.004, 0.14 + s * 0.005), v2(0.0, -s * 0.0005)}};
    for (const Approach& approach : approaches) {
      PlanarProxyState state;
      for (int k = 0; k <= 24; ++k) {  // up to 7 mm into the solid
        const Vec2 x = approach.start + approach.step * k;
        PlanarInput input;
        input.x_m = x;
        const Vec2 closed = box.force_N(input, state);
        CHECK(near(state.proxy_m, box.open_loop_proxy_m(x)));
        CHECK(near(closed, box.open_loop_force_N(input), 1e-12));
      }
    }
  }
}

TEST_CASE("planar box: the closed-loop proxy stays on the side the handle came in by") {
  const PlanarBox box = PlanarBox::make(v2(-0.02, 0.10), v2(0.02, 0.14), 400.0, true);
  PlanarProxyState state;
  // In through the left side, then past the middle towards the right side.
  run(box, state, {v2(-0.03, 0.12), v2(-0.019, 0.12), v2(0.0, 0.121), v2(0.015, 0.122)});
  CHECK(near(state.proxy_m, v2(-0.02, 0.122)));
  CHECK(state.contact == ProxyContact::edge);
  CHECK(state.feature == 3);  // edges: bottom, right, top, left
  // The open loop would push out through the right side.
  CHECK(box.open_loop_proxy_m(v2(0.015, 0.122)) == v2(0.02, 0.122));
  // Up and out over the top-left corner: free again.
  CHECK(run(box, state, {v2(0.015, 0.145)}) == v2(0.0, 0.0));
  CHECK(state.contact == ProxyContact::none);
}

TEST_CASE("planar box: a handle exactly on an edge is free, from there, in is caught") {
  const PlanarBox box = PlanarBox::make(v2(-0.02, 0.10), v2(0.02, 0.14), 400.0, true);
  PlanarProxyState state;
  CHECK(run(box, state, {v2(0.0, 0.09), v2(0.005, 0.10)}) == v2(0.0, 0.0));
  CHECK(state.contact == ProxyContact::none);
  CHECK(run(box, state, {v2(0.006, 0.1002)})[1] == doctest::Approx(400.0 * -0.0002));
  CHECK(near(state.proxy_m, v2(0.006, 0.10)));
  // Along the edge, on it: no force, and the contact is let go only once outside.
  CHECK(run(box, state, {v2(0.008, 0.10)}) == v2(0.0, 0.0));
  CHECK(run(box, state, {v2(0.009, 0.0999)}) == v2(0.0, 0.0));
  CHECK(state.contact == ProxyContact::none);
}

TEST_CASE("planar box: a thin box swept across in one tick does not pop through") {
  // 0.5 mm thick, 100 mm long; the handle jumps 20 mm across it in one tick.
  const PlanarBox box = PlanarBox::make(v2(-0.05, 0.0), v2(0.05, 0.0005), 1000.0, true);
  PlanarProxyState state;
  const Vec2 f = run(box, state, {v2(0.001, 0.01), v2(0.001, -0.01)});
  CHECK(near(state.proxy_m, v2(0.001, 0.0005)));
  CHECK(f[1] == doctest::Approx(1000.0 * 0.0105));
  // Sliding along under it keeps the proxy on top; past the end it lets go.
  run(box, state, {v2(0.03, -0.012)});
  CHECK(near(state.proxy_m, v2(0.03, 0.0005)));
  CHECK(run(box, state, {v2(0.06, -0.012)}) == v2(0.0, 0.0));
}

TEST_CASE("planar box: a cage holds the handle at a corner and starts passive when outside") {
  const PlanarBox cage = PlanarBox::make(v2(-0.02, 0.10), v2(0.02, 0.14), 400.0, false);
  PlanarProxyState state;
  run(cage, state, {v2(0.0, 0.12), v2(0.019, 0.139), v2(0.03, 0.15), v2(0.025, 0.16)});
  CHECK(state.proxy_m == v2(0.02, 0.14));
  CHECK(state.contact == ProxyContact::vertex);
  // Back inside: free.
  CHECK(run(cage, state, {v2(0.0, 0.12)}) == v2(0.0, 0.0));

  // Starting outside the cage (in its solid): no force until the handle is inside.
  PlanarProxyState outside;
  CHECK(run(cage, outside, {v2(0.05, 0.12), v2(0.04, 0.12), v2(0.03, 0.13)}) == v2(0.0, 0.0));
  run(cage, outside, {v2(0.01, 0.12)});
  CHECK(run(cage, outside, {v2(0.03, 0.12)}) == v2(400.0 * (0.02 - 0.03), 0.0));
}

TEST_CASE("planar circle: open loop, inside and outside, at the centre") {
  const PlanarCircle disc = parse_as<PlanarCircle>(
      R"({"type": "circle", "center": ["0 mm", "120 mm"], "radius": "15 mm", "stiffness": 300, "solid": "inside"})");
  CHECK(disc.open_loop_force_N(at(0.0, 0.10)) == v2(0.0, 0.0));
  CHECK(disc.open_loop_force_N(at(0.015, 0.12)) == v2(0.0, 0.0));  // on the circle
  const Vec2 x = v2(0.003, 0.124);
  const double dx = 0.003, dy = 0.124 - 0.12, distance = std::sqrt(dx * dx + dy * dy);
  const Vec2 proxy = v2(0.0 + dx * (0.015 / distance), 0.12 + dy * (0.015 / distance));
  CHECK(disc.open_loop_proxy_m(x) == proxy);
  CHECK(disc.open_loop_force_N(at(0.003, 0.124)) == v2(300.0 * (proxy[0] - x[0]), 300.0 * (proxy[1] - x[1])));
  CHECK(disc.open_loop_proxy_m(v2(0.0, 0.12)) == v2(0.015, 0.12));  // the centre: +x

  const PlanarCircle ring{.center_m = v2(0.0, 0.12), .radius_m = 0.015, .stiffness_N_per_m = 300.0, .solid_inside = false};
  CHECK(ring.open_loop_force_N(at(0.003, 0.124)) == v2(0.0, 0.0));
  CHECK(near(ring.open_loop_proxy_m(v2(0.0, 0.14)), v2(0.0, 0.135)));
  CHECK(ring.open_loop_force_N(at(0.0, 0.14))[1] == doctest::Approx(300.0 * -0.005));
}

TEST_CASE("planar circle: closed loop equals open loop after an approach, passive start, centre") {
  const PlanarCircle disc{.center_m = v2(0.0, 0.12), .radius_m = 0.015, .stiffness_N_per_m = 300.0, .solid_inside = true};
  PlanarProxyState state;
  for (int k = 0; k <= 20; ++k) {  // along the normal through (0.02, 0.12) towards the centre
    PlanarInput input;
    input.x_m = v2(0.02 - 0.0005 * k, 0.12);
    CHECK(disc.force_N(input, state) == disc.open_loop_force_N(input));
    CHECK(state.proxy_m == disc.open_loop_proxy_m(input.x_m));
  }
  // At the centre the proxy stays where it was (the open loop's fixed +x happens to agree here).
  run(disc, state, {v2(0.001, 0.121)});
  const Vec2 before = state.proxy_m;
  run(disc, state, {v2(0.0, 0.12)});
  CHECK(state.proxy_m == before);

  // Straight to the centre from outside: the point where the path met the circle.
  PlanarProxyState straight;
  run(disc, straight, {v2(0.0, 0.10), v2(0.0, 0.12)});
  CHECK(near(straight.proxy_m, v2(0.0, 0.105)));

  // Started inside: no force until out.
  PlanarProxyState inside;
  CHECK(run(disc, inside, {v2(0.0, 0.125), v2(0.005, 0.12)}) == v2(0.0, 0.0));
  run(disc, inside, {v2(0.0, 0.14)});
  CHECK(run(disc, inside, {v2(0.0, 0.13)})[1] > 0.0);

  // The cage: the same after an approach from inside.
  const PlanarCircle ring{.center_m = v2(0.0, 0.12), .radius_m = 0.015, .stiffness_N_per_m = 300.0, .solid_inside = false};
  PlanarProxyState cage;
  for (int k = 0; k <= 20; ++k) {
    PlanarInput input;
    input.x_m = v2(0.0, 0.12 + 0.001 * k);
    CHECK(ring.force_N(input, cage) == ring.open_loop_force_N(input));
  }
}

TEST_CASE("planar shapes: can_act_within a rectangular workspace") {
  const Vec2 low = v2(-0.05, 0.05), high = v2(0.05, 0.15);
  CHECK(PlanarWall{.point_m = v2(0.0, 0.1), .normal = v2(0.0, -1.0), .stiffness_N_per_m = 1.0}.can_act_within(low, high));
  CHECK_FALSE(PlanarWall{.point_m = v2(0.0, 0.2), .normal = v2(0.0, -1.0), .stiffness_N_per_m = 1.0}.can_act_within(low, high));
  CHECK_FALSE(PlanarBox::make(v2(0.1, 0.0), v2(0.2, 0.1), 1.0, true).can_act_within(low, high));
  CHECK(PlanarBox::make(v2(0.0, 0.0), v2(0.2, 0.1), 1.0, true).can_act_within(low, high));
  CHECK_FALSE(PlanarBox::make(v2(-0.1, 0.0), v2(0.1, 0.2), 1.0, false).can_act_within(low, high));
  CHECK(PlanarCircle{.center_m = v2(0.0, 0.1), .radius_m = 0.01, .stiffness_N_per_m = 1.0}.can_act_within(low, high));
  CHECK_FALSE(PlanarCircle{.center_m = v2(0.0, 0.3), .radius_m = 0.01, .stiffness_N_per_m = 1.0}.can_act_within(low, high));
  CHECK_FALSE(PlanarCircle{.center_m = v2(0.0, 0.1), .radius_m = 0.2, .stiffness_N_per_m = 1.0, .solid_inside = false}
                  .can_act_within(low, high));
}

}  // namespace HAPSCENE_TEST_FILE
