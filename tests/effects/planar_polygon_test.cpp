// The polygon's god-object proxy: convex and concave corners, thin walls swept fast,
// vertices hit exactly, friction (stick, then slip), a run that starts inside, open loop
// (nearest point) against closed loop, and the grid that keeps the tick's work small.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "engine/base/polygon.hpp"
#include "tests/effects/planar_test_support.hpp"

using namespace hapscene;
using namespace hapscene::planar_test;

namespace {

Vec2 step(const PlanarPolygon& polygon, PlanarProxyState& state, const Vec2& x) {
  PlanarInput input;
  input.x_m = x;
  return polygon.force_N(input, state);
}

PlanarPolygon make_polygon(std::vector<Vec2> points, bool solid_inside, double stiffness = 1000.0,
                           FrictionCoefficients friction = {}) {
  REQUIRE(simple_polygon_problem(points).empty());
  PlanarPolygon polygon;
  polygon.outline = PolygonOutline(points, solid_inside);
  polygon.stiffness_N_per_m = stiffness;
  polygon.friction = friction;
  return polygon;
}

bool near(const Vec2& a, const Vec2& b, double tolerance = 1e-15) {
  return std::fabs(a[0] - b[0]) <= tolerance && std::fabs(a[1] - b[1]) <= tolerance;
}

// A solid U (30 x 30 mm) with a free notch x in [10, 20] mm, y in [10, 30] mm: the
// notch's bottom corners are concave corners of the free space.
std::vector<Vec2> u_shape() {
  return {v2(0.0, 0.0),   v2(0.03, 0.0),  v2(0.03, 0.03), v2(0.02, 0.03),
          v2(0.02, 0.01), v2(0.01, 0.01), v2(0.01, 0.03), v2(0.0, 0.03)};
}

// A regular polygon of n points around (cx, cy).
std::vector<Vec2> regular(int n, double radius, double cx = 0.0, double cy = 0.0) {
  std::vector<Vec2> points;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n;
    points.push_back(v2(cx + radius * std::cos(angle), cy + radius * std::sin(angle)));
  }
  return points;
}

}  // namespace

TEST_CASE("planar polygon: convex vertices are wide, concave ones narrow, normals point to free space") {
  const PolygonOutline solid(u_shape(), true);
  CHECK(solid.wide(0));
  CHECK_FALSE(solid.wide(4));  // (20, 10) mm: the notch's bottom right
  CHECK_FALSE(solid.wide(5));
  CHECK(solid.normal(0) == v2(0.0, -1.0));  // bottom edge: free below
  CHECK(solid.normal(4) == v2(0.0, 1.0));   // notch bottom: free above
  // The same points clockwise: the same geometry.
  const std::vector<Vec2> anticlockwise = u_shape();
  const std::vector<Vec2> reversed(anticlockwise.rbegin(), anticlockwise.rend());
  const PolygonOutline clockwise(reversed, true);
  CHECK(clockwise.in_solid(v2(0.005, 0.005)));
  CHECK_FALSE(clockwise.in_solid(v2(0.015, 0.02)));
  CHECK(clockwise.wide(0));
  CHECK_FALSE(clockwise.wide(2));  // u_shape()[5]
  CHECK_FALSE(clockwise.wide(3));  // u_shape()[4]
  CHECK(clockwise.normal(0) == v2(0.0, 1.0));  // the left arm's top, from (0, 30) to (10, 30) mm: free above
  // As a cage the sides swap.
  const PolygonOutline cage(u_shape(), false);
  CHECK(cage.normal(0) == v2(0.0, 1.0));
  CHECK_FALSE(cage.wide(0));
  CHECK(cage.wide(4));
  CHECK(cage.in_solid(v2(0.015, 0.02)));
}

TEST_CASE("planar polygon: a concave corner holds the proxy") {
  const PlanarPolygon u = make_polygon(u_shape(), true);
  PlanarProxyState state;
  step(u, state, v2(0.015, 0.04));
  step(u, state, v2(0.015, 0.02));
  step(u, state, v2(0.012, 0.011));
  CHECK(state.contact == ProxyContact::none);
  // Down onto the bottom of the notch: on the edge.
  step(u, state, v2(0.012, 0.008));
  CHECK(near(state.proxy_m, v2(0.012, 0.01)));
  CHECK(state.contact == ProxyContact::edge);
  // Down and left into the corner: held there, pushed back diagonally.
  const Vec2 f = step(u, state, v2(0.008, 0.007));
  CHECK(state.proxy_m == v2(0.01, 0.01));
  CHECK(state.contact == ProxyContact::vertex);
  CHECK(f == v2(1000.0 * (0.01 - 0.008), 1000.0 * (0.01 - 0.007)));
  // Further into the corner region: still held.
  step(u, state, v2(0.005, 0.002));
  CHECK(state.proxy_m == v2(0.01, 0.01));
  // Up along the left wall of the notch (into the wall only): slides up that wall.
  step(u, state, v2(0.008, 0.015));
  CHECK(near(state.proxy_m, v2(0.01, 0.015)));
  // Back into the notch: free.
  CHECK(step(u, state, v2(0.015, 0.02)) == v2(0.0, 0.0));
}

TEST_CASE("planar polygon: a thin wall swept fast does not pop through, at any angle") {
  // A 0.2 mm thick bar, 80 mm long, turned by several angles; the handle crosses it in
  // one tick (30 mm: 30 m/s at 1 kHz) through its middle, and from other points.
  for (const double angle : {0.0, 0.3, 1.0, M_PI / 2, 2.5}) {
    const Vec2 along = v2(std::cos(angle), std::sin(angle));
    const Vec2 across = v2(-along[1], along[0]);
    const Vec2 centre = v2(0.01, 0.12);
    std::vector<Vec2> bar = {centre - along * 0.04 - across * 0.0001, centre + along * 0.04 - across * 0.0001,
                             centre + along * 0.04 + across * 0.0001, centre - along * 0.04 + across * 0.0001};
    const PlanarPolygon polygon = make_polygon(bar, true);
    for (const double offset : {-0.03, 0.0, 0.017}) {
      PlanarProxyState state;
      step(polygon, state, centre + along * offset + across * 0.015);
      const Vec2 f = step(polygon, state, centre + along * offset - across * 0.015);
      // The proxy stays on the side the handle came from; the force pulls it back across.
      CHECK(dot(state.proxy_m - centre, across) == doctest::Approx(0.0001).epsilon(1e-6));
      CHECK(dot(f, across) == doctest::Approx(1000.0 * 0.0151).epsilon(1e-9));
      // Deeper still, sliding along: it stays.
      step(polygon, state, centre + along * (offset + 0.005) - across * 0.02);
      CHECK(dot(state.proxy_m - centre, across) == doctest::Approx(0.0001).epsilon(1e-6));
    }
  }
}

TEST_CASE("planar polygon: a path through a vertex exactly stops there, never inside") {
  // A diamond; the handle comes straight down through its top vertex.
  const PlanarPolygon diamond =
      make_polygon({v2(0.0, 0.01), v2(-0.01, 0.0), v2(0.0, -0.01), v2(0.01, 0.0)}, true);
  PlanarProxyState state;
  step(diamond, state, v2(0.0, 0.02));
  step(diamond, state, v2(0.0, 0.0));
  // It slid to the foot on one of the two upper edges (equally near): a convex corner
  // does not hold, pressing along its bisector slides off to a side.
  REQUIRE(state.contact == ProxyContact::edge);
  CHECK((state.feature == 0 || state.feature == 3));
  CHECK(std::fabs(diamond.outline.side(state.feature, state.proxy_m)) < 1e-17);
  CHECK(norm(state.proxy_m - v2(0.0, 0.0)) == doctest::Approx(0.01 / std::sqrt(2.0)));
  CHECK(state.proxy_m[1] == doctest::Approx(0.005));
}

TEST_CASE("planar polygon: a handle that jumps past a convex corner is let go, not held") {
  // In through the left side, out above the top in the same tick: the proxy slides up the
  // left side to the corner, where the handle is on the free side of the top, and follows it.
  const PlanarPolygon square = make_polygon({v2(-0.005, -0.005), v2(0.005, -0.005), v2(0.005, 0.005), v2(-0.005, 0.005)}, true);
  PlanarProxyState state;
  step(square, state, v2(-0.02, 0.0));
  CHECK(step(square, state, v2(0.004, 0.007)) == v2(0.0, 0.0));
  CHECK(state.contact == ProxyContact::none);
  // Through the middle instead: held on the left side.
  PlanarProxyState held;
  step(square, held, v2(-0.02, 0.0));
  step(square, held, v2(0.004, 0.001));
  CHECK(near(held.proxy_m, v2(-0.005, 0.001)));
}

TEST_CASE("planar polygon: friction sticks within mu_s of the normal force, then slides with mu_d") {
  // A solid floor y < 0 (a wide rectangle), mu_s 0.5, mu_d 0.3.
  const PlanarPolygon floor = make_polygon({v2(-0.1, -0.1), v2(0.1, -0.1), v2(0.1, 0.0), v2(-0.1, 0.0)}, true,
                                           1000.0, FrictionCoefficients{0.5, 0.3});
  PlanarProxyState state;
  step(floor, state, v2(0.0, 0.01));
  step(floor, state, v2(0.0, -0.002));  // pressed 2 mm in: normal force 2 N
  CHECK(near(state.proxy_m, v2(0.0, 0.0)));
  // 0.9 mm sideways: tangential 0.9 N <= 0.5 x 2 N: sticks.
  Vec2 f = step(floor, state, v2(0.0009, -0.002));
  CHECK(near(state.proxy_m, v2(0.0, 0.0)));
  CHECK_FALSE(state.sliding);
  CHECK(f[0] == doctest::Approx(-0.9));
  CHECK(std::fabs(f[0]) <= 0.5 * f[1]);
  // 1.5 mm: beyond the static cone: slides, lagging mu_d x depth = 0.6 mm behind.
  f = step(floor, state, v2(0.0015, -0.002));
  CHECK(state.sliding);
  CHECK(state.proxy_m[0] == doctest::Approx(0.0009));
  CHECK(f[0] == doctest::Approx(-0.3 * f[1]));
  // Keeps sliding with the dynamic cone.
  f = step(floor, state, v2(0.0020, -0.002));
  CHECK(state.proxy_m[0] == doctest::Approx(0.0014));
  CHECK(f[0] == doctest::Approx(-0.3 * f[1]));
  // Stops moving: within the dynamic cone, so it sticks again.
  step(floor, state, v2(0.0019, -0.002));
  CHECK_FALSE(state.sliding);
  CHECK(state.proxy_m[0] == doctest::Approx(0.0014));
  // Back the other way by 0.9 mm: sticks (static cone).
  f = step(floor, state, v2(0.0005, -0.002));
  CHECK(state.proxy_m[0] == doctest::Approx(0.0014));
  CHECK(f[0] == doctest::Approx(0.9));
  // Pressing harder widens the cone: 3 mm deep, 1.4 mm sideways sticks.
  step(floor, state, v2(0.0, -0.003));
  CHECK(state.proxy_m[0] == doctest::Approx(0.0014));
  // Lifting off clears the contact.
  CHECK(step(floor, state, v2(0.0, 0.001)) == v2(0.0, 0.0));
  CHECK(state.contact == ProxyContact::none);
}

TEST_CASE("planar polygon: friction does not let the proxy into a corner it cannot reach") {
  // Friction on the U's notch floor, sliding into the concave corner: held at the corner.
  const PlanarPolygon u = make_polygon(u_shape(), true, 1000.0, FrictionCoefficients{0.2, 0.1});
  PlanarProxyState state;
  step(u, state, v2(0.018, 0.02));
  step(u, state, v2(0.018, 0.009));
  for (double x = 0.018; x > 0.0; x -= 0.001) step(u, state, v2(x, 0.005));
  CHECK(state.proxy_m == v2(0.01, 0.01));
  CHECK_FALSE(u.outline.in_solid(state.proxy_m));
}

TEST_CASE("planar polygon: non-finite input gives no force and keeps the proxy") {
  const PlanarPolygon u = make_polygon(u_shape(), true);
  PlanarProxyState state;
  step(u, state, v2(0.015, 0.02));
  step(u, state, v2(0.012, 0.008));
  const PlanarProxyState before = state;
  CHECK(step(u, state, v2(NAN, 0.008)) == v2(0.0, 0.0));
  CHECK(step(u, state, v2(0.01, INFINITY)) == v2(0.0, 0.0));
  CHECK(state.proxy_m == before.proxy_m);
  CHECK(state.contact == before.contact);
  CHECK(step(u, state, v2(0.012, 0.008)) == v2(0.0, 1000.0 * (0.01 - 0.008)));
}

TEST_CASE("planar polygon: a run that starts inside follows the handle until it leaves") {
  const PlanarPolygon square = make_polygon({v2(0.0, 0.0), v2(0.02, 0.0), v2(0.02, 0.02), v2(0.0, 0.02)}, true);
  PlanarProxyState state;
  CHECK(step(square, state, v2(0.01, 0.01)) == v2(0.0, 0.0));
  CHECK(step(square, state, v2(0.015, 0.012)) == v2(0.0, 0.0));
  CHECK(step(square, state, v2(0.025, 0.012)) == v2(0.0, 0.0));  // out through the right side
  CHECK(step(square, state, v2(0.019, 0.012))[0] == doctest::Approx(1000.0 * 0.001));
}

TEST_CASE("planar polygon: open loop is the nearest boundary point, closed loop agrees along normals") {
  const PlanarPolygon u = make_polygon(u_shape(), true);
  CHECK(u.open_loop_proxy_m(v2(0.015, 0.02)) == v2(0.015, 0.02));      // in the notch: free
  CHECK(u.open_loop_proxy_m(v2(0.029, 0.015)) == v2(0.03, 0.015));     // near the right side
  CHECK(u.open_loop_proxy_m(v2(0.005, 0.0285)) == v2(0.005, 0.03));    // near the left arm's top
  CHECK(u.open_loop_proxy_m(v2(0.0095, 0.0095)) == v2(0.01, 0.01));    // near the notch's corner: the corner
  // Approach along the normal of several edges, 0.2 mm a tick, up to 4 mm deep.
  struct Approach {
    Vec2 start, step;
  };
  for (const Approach& a : {Approach{v2(0.035, 0.015), v2(-0.0002, 0.0)}, Approach{v2(0.015, -0.005), v2(0.0, 0.0002)},
                            Approach{v2(0.015, 0.015), v2(0.0, -0.0002)}, Approach{v2(0.005, 0.035), v2(0.0, -0.0002)}}) {
    PlanarProxyState state;
    for (int k = 0; k <= 45; ++k) {
      const Vec2 x = a.start + a.step * k;
      PlanarInput input;
      input.x_m = x;
      const Vec2 closed = u.force_N(input, state);
      CHECK(near(state.proxy_m, u.open_loop_proxy_m(x)));
      CHECK(near(closed, u.open_loop_force_N(input), 1e-12));
    }
  }
}

TEST_CASE("planar polygon: the grid lists few edges per cell for 1000 edges") {
  const PolygonOutline ring(regular(1000, 0.05, 0.0, 0.12), true);
  CHECK(ring.grid_columns() * ring.grid_rows() >= 500);
  CHECK(ring.most_edges_per_cell() <= 16);
  // A maze-like zigzag: long thin teeth.
  std::vector<Vec2> comb;
  for (int i = 0; i < 250; ++i) {
    comb.push_back(v2(0.0004 * i, 0.0));
    comb.push_back(v2(0.0004 * i + 0.0002, 0.05));
  }
  comb.push_back(v2(0.1, -0.01));
  comb.push_back(v2(0.0, -0.01));
  REQUIRE(simple_polygon_problem(comb).empty());
  const PolygonOutline teeth(comb, true);
  CHECK(teeth.most_edges_per_cell() <= 40);
}

TEST_CASE("planar polygon: 1000 edges, the proxy slides round with a circling handle") {
  const PlanarPolygon ring = make_polygon(regular(1000, 0.05, 0.0, 0.12), true);
  PlanarProxyState state;
  // Press 2 mm in, then go round once at 2 mm depth in 4000 ticks (sliding along the edges).
  step(ring, state, v2(0.06, 0.12));
  for (int k = 0; k <= 4000; ++k) {
    const double angle = 2.0 * M_PI * k / 4000.0;
    const Vec2 x = v2(0.048 * std::cos(angle), 0.12 + 0.048 * std::sin(angle));
    step(ring, state, x);
    // On the edge it slid along, the nearest one or (in the thin wedge about a vertex
    // where two feet lie on their edges) its neighbour: as near to x to within 0.1 um.
    const double closed_m = norm(state.proxy_m - x);
    const double open_m = norm(ring.open_loop_proxy_m(x) - x);
    REQUIRE(closed_m >= open_m - 1e-15);
    REQUIRE(closed_m - open_m < 1e-7);
    REQUIRE(closed_m > 0.0019);
  }
}

TEST_CASE("planar polygon: tick time with 1000 edges" * doctest::skip()) {
  // Run with: build/tests/hapscene_tests -tc='*tick time with 1000 edges*' --no-skip
  const PlanarPolygon ring = make_polygon(regular(1000, 0.05, 0.0, 0.12), true);
  PlanarProxyState state;
  std::vector<double> batch_ns;
  double sink = 0.0;
  constexpr int kBatch = 1000;
  int k = 0;
  for (int batch = 0; batch < 400; ++batch) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kBatch; ++i, ++k) {
      // Round the ring in and out: 1.5 mm a tick, radius 44 to 56 mm (free, contact, leaving).
      const double angle = 2.0 * M_PI * k / 200.0;
      const double radius = 0.05 + 0.006 * std::sin(2.0 * M_PI * k / 37.0);
      PlanarInput input;
      input.x_m = v2(radius * std::cos(angle), 0.12 + radius * std::sin(angle));
      sink += ring.force_N(input, state)[0];
    }
    const auto stop = std::chrono::steady_clock::now();
    batch_ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count() / kBatch);
  }
  std::sort(batch_ns.begin(), batch_ns.end());
  std::printf("1000-edge regular polygon: median %.1f ns per tick (batches of %d), p90 %.1f ns (sink %g)\n",
              batch_ns[batch_ns.size() / 2], kBatch, batch_ns[batch_ns.size() * 9 / 10], sink);
  CHECK(batch_ns[batch_ns.size() / 2] < 1000.0);

  // A comb of 1000 edges (250 teeth 0.4 mm apart, 50 mm long), the handle sweeping
  // across the teeth and back, 1 mm a tick, pressed in between them.
  std::vector<Vec2> comb;
  for (int i = 0; i < 499; ++i) {
    comb.push_back(v2(0.0002 * i, 0.0));
    comb.push_back(v2(0.0002 * i + 0.0001, 0.05));
  }
  comb.push_back(v2(0.1, -0.01));
  comb.push_back(v2(0.0, -0.01));
  const PlanarPolygon teeth = make_polygon(comb, true);
  REQUIRE(teeth.outline.edge_count() == 1000);
  PlanarProxyState comb_state;
  batch_ns.clear();
  for (int batch = 0; batch < 400; ++batch) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kBatch; ++i, ++k) {
      const double phase = (k % 200) / 100.0;
      PlanarInput input;
      input.x_m = v2(0.1 * (phase < 1.0 ? phase : 2.0 - phase), 0.03 + 0.025 * std::sin(k * 0.05));
      sink += teeth.force_N(input, comb_state)[0];
    }
    const auto stop = std::chrono::steady_clock::now();
    batch_ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count() / kBatch);
  }
  std::sort(batch_ns.begin(), batch_ns.end());
  std::printf("1000-edge comb: median %.1f ns per tick (batches of %d), p90 %.1f ns (sink %g)\n",
              batch_ns[batch_ns.size() / 2], kBatch, batch_ns[batch_ns.size() * 9 / 10], sink);
  CHECK(batch_ns[batch_ns.size() / 2] < 1000.0);
}

TEST_CASE("planar polygon: random star polygons and wild handle paths never put the proxy inside") {
  // Star-shaped polygons (simple by construction) with deep concave notches, solid inside
  // and as cages, with and without friction; the handle wanders with jumps of up to 60 mm
  // a tick. The proxy, having started in free space, must never be inside the solid
  // (points on the outline, to rounding, count as outside).
  std::uint64_t seed = 12345;
  const auto uniform = [&seed] {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) * 0x1.0p-53;
  };
  int contacts = 0;
  for (int shape = 0; shape < 32; ++shape) {
    // Small outlines (a grid of a few cells) and large ones (hundreds of cells).
    const int n = shape < 24 ? 5 + static_cast<int>(uniform() * 60) : 200 + static_cast<int>(uniform() * 400);
    std::vector<Vec2> points;
    for (int i = 0; i < n; ++i) {
      const double angle = 2.0 * M_PI * (i + 0.8 * uniform()) / n;
      const double radius = 0.005 + 0.04 * uniform();
      points.push_back(v2(radius * std::cos(angle), 0.1 + radius * std::sin(angle)));
    }
    if (!simple_polygon_problem(points).empty()) continue;
    const bool solid_inside = shape % 2 == 0;
    const FrictionCoefficients friction = shape % 3 == 0 ? FrictionCoefficients{0.6, 0.4} : FrictionCoefficients{};
    const PlanarPolygon polygon = make_polygon(points, solid_inside, 1000.0, friction);
    // Start in free space: far out for a solid, at the centre region for a cage.
    Vec2 x = solid_inside ? v2(0.2, 0.1) : v2(0.0, 0.1);
    if (!solid_inside && polygon.outline.in_solid(x)) continue;
    PlanarProxyState state;
    for (int tick = 0; tick < 3000; ++tick) {
      const double jump = uniform() < 0.05 ? 0.06 : 0.002;
      x = x + v2((uniform() - 0.5) * jump, (uniform() - 0.5) * jump);
      x = v2(std::clamp(x[0], -0.06, 0.06), std::clamp(x[1], 0.04, 0.16));
      step(polygon, state, x);
      contacts += state.contact != ProxyContact::none;
      if (polygon.outline.in_solid(state.proxy_m)) {
        const double off_outline_m = norm(polygon.outline.nearest_point(state.proxy_m) - state.proxy_m);
        REQUIRE(off_outline_m < 1e-12);
      }
    }
  }
  CHECK(contacts > 10000);  // the paths did press into the shapes
}

TEST_CASE("planar polygon: a proxy left far behind catches up over a few ticks, on the outline") {
  // A comb of thin teeth; the handle, pressed into one tooth's side, is moved at once
  // 40 teeth along, just below their tips (through the teeth): the proxy climbs over
  // tooth after tooth, a bounded number per tick, staying on the outline, until it rests
  // against the first tooth the handle is behind (where the foot of the perpendicular
  // from the handle falls below the tip).
  std::vector<Vec2> comb;
  for (int i = 0; i < 100; ++i) {
    comb.push_back(v2(0.001 * i, 0.0));
    comb.push_back(v2(0.001 * i + 0.0005, 0.05));
  }
  comb.push_back(v2(0.1, -0.01));
  comb.push_back(v2(0.0, -0.01));
  const PlanarPolygon teeth = make_polygon(comb, true);
  PlanarProxyState state;
  step(teeth, state, v2(0.0102, 0.03));  // in the gap between teeth 10 and 11
  step(teeth, state, v2(0.0108, 0.03));  // into tooth 11's left side
  REQUIRE(state.contact == ProxyContact::edge);
  const Vec2 target = v2(0.0508, 0.0499);
  double previous_gap_m = norm(state.proxy_m - target);
  int moving_ticks = 0;
  for (int tick = 0; tick < 30; ++tick) {
    const Vec2 before = state.proxy_m;
    step(teeth, state, target);
    CHECK(norm(teeth.outline.nearest_point(state.proxy_m) - state.proxy_m) < 1e-12);  // on the outline
    const double gap_m = norm(state.proxy_m - target);
    CHECK(gap_m <= previous_gap_m);
    previous_gap_m = gap_m;
    moving_ticks += !(state.proxy_m == before);
  }
  CHECK(moving_ticks > 1);   // more than one tick's work
  CHECK(moving_ticks < 10);  // but not many
  CHECK(state.contact == ProxyContact::edge);
  CHECK(state.proxy_m[0] > 0.035);
  // Lifted above the tips: free at once.
  CHECK(step(teeth, state, v2(0.0508, 0.0505)) == v2(0.0, 0.0));
}
