// scripts/planar/maze.lua: a labyrinth of wall bars with a proxy written in the script.
// Closed loop (one instance called along a path, as a run calls it) the proxy holds in a
// concave corner, slides along a wall, and never lets the handle through the 0.5 mm fin
// however far the handle jumps in one call; open loop (fresh instances) each point inside
// a wall is pushed out through the nearest free face.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/harness/planar_open_loop.hpp"
#include "engine/load/environment.hpp"
#include "tests/lua/script_test_support.hpp"
#include "tests/support.hpp"

namespace hapscene {
namespace {

constexpr double kStiffness_N_per_m = 200.0;

std::unique_ptr<ScriptInstance> start_maze() {
  auto script = ScriptInstance::create(compile_script("scripts/planar/maze.lua", test::read_script("planar/maze.lua"),
                                                      nlohmann::json::object(), "env.json", "/effects/0/params", {}, 2));
  script->reset();
  return script;
}

// One call at (x, y) mm; the force in N.
Vec2 at_mm(ScriptInstance& script, double x_mm, double y_mm) {
  return script.force_N(PlanarScriptInput{Vec2{{x_mm * 1e-3, y_mm * 1e-3}}, Vec2{}, 0.0, 0.001});
}

// The proxy the force implies: p + F / K, in mm.
double proxy_x_mm(const Vec2& f, double x_mm) { return x_mm + f[0] / kStiffness_N_per_m * 1e3; }
double proxy_y_mm(const Vec2& f, double y_mm) { return y_mm + f[1] / kStiffness_N_per_m * 1e3; }

}  // namespace

TEST_CASE("maze: the proxy holds in a concave corner however the handle presses into it") {
  // The corner between the left wall's face x = -58 mm and the shelf's top y = 122 mm.
  auto script = start_maze();
  CHECK(at_mm(*script, -50, 130)[0] == 0.0);
  // Pressed diagonally into the corner, in steps, then deep beyond both walls.
  for (double k = 0; k <= 1.0; k += 0.01) at_mm(*script, -50 - 14 * k, 130 - 14 * k);
  const Vec2 f = at_mm(*script, -64, 116);
  CHECK(proxy_x_mm(f, -64) == doctest::Approx(-58).epsilon(1e-9));
  CHECK(proxy_y_mm(f, 116) == doctest::Approx(122).epsilon(1e-9));
  CHECK(f[0] > 0.0);
  CHECK(f[1] > 0.0);
  // Wiggling in the corner region does not free the proxy.
  for (int i = 0; i < 200; ++i) {
    const double x = -61 + 2 * std::sin(i * 0.3);
    const double y = 119 + 2 * std::cos(i * 0.7);
    const Vec2 g = at_mm(*script, x, y);
    CHECK(proxy_x_mm(g, x) >= -58 - 1e-9);
    CHECK(proxy_y_mm(g, y) >= 122 - 1e-9);
  }
  CHECK_FALSE(script->disabled());
}

TEST_CASE("maze: a fast sweep never pops through the thin fin") {
  // The fin: x in (-45.25, -44.75) mm, y in (135, 159) mm. Approached from the left.
  for (const double jump_mm : {1.0, 5.0, 10.0, 20.0, 40.0}) {
    CAPTURE(jump_mm);
    auto script = start_maze();
    at_mm(*script, -50, 150);
    // One call moves the handle from the left of the fin to jump_mm beyond it (up to
    // 40 m/s at 1 kHz), then it goes on sweeping to the right.
    for (double x = -44.75 + jump_mm; x <= -44.75 + jump_mm + 10; x += 1.0) {
      const Vec2 f = at_mm(*script, x, 150);
      CHECK(proxy_x_mm(f, x) == doctest::Approx(-45.25).epsilon(1e-12));
      CHECK(f[0] < 0.0);  // pulled back to the side it came from
    }
    // A penetration renderer would push through the nearer far face: the proxy does not.
    const Vec2 inside = at_mm(*script, -44.9, 150);
    CHECK(proxy_x_mm(inside, -44.9) == doctest::Approx(-45.25).epsilon(1e-12));
    CHECK(inside[0] < 0.0);
  }
  // Diagonal sweeps across the fin at any slope are held too.
  auto script = start_maze();
  at_mm(*script, -52, 140);
  const Vec2 f = at_mm(*script, -38, 152);
  CHECK(proxy_x_mm(f, -38) == doctest::Approx(-45.25).epsilon(1e-12));
  CHECK(proxy_y_mm(f, 152) == doctest::Approx(152).epsilon(1e-9));  // slid along the fin to level
}

TEST_CASE("maze: the proxy slides along a wall and comes off it at its end") {
  auto script = start_maze();
  at_mm(*script, -20, 150);
  // Pressed 3 mm into the ledge's top (y = 140 mm) from above, sliding right.
  at_mm(*script, -2, 141);
  for (double x = -2; x <= 20; x += 0.5) {
    const Vec2 f = at_mm(*script, x, 137);
    CHECK(proxy_y_mm(f, 137) == doctest::Approx(140).epsilon(1e-12));
    CHECK(proxy_x_mm(f, x) == doctest::Approx(x).epsilon(1e-9));
    CHECK(f[1] == doctest::Approx(0.6));
  }
  // Back out above the ledge: no force.
  const Vec2 free = at_mm(*script, 20, 145);
  CHECK(free[0] == 0.0);
  CHECK(free[1] == 0.0);
}

TEST_CASE("maze: open loop pushes out of a wall through the nearest free face, never into another wall") {
  const PlanarScene scene = load_planar_environment_file(test::source_path("environments/planar/haplink_maze.json"));
  PlanarOpenLoop open_loop(scene);
  // In the shelf beside the left wall: its nearest face is the left wall's (inside the
  // shelf), so the push goes up out of the shelf.
  const Vec2 f = open_loop.force_N(Vec2{{-57.5e-3, 121.5e-3}}, Vec2{});
  CHECK(f[0] == 0.0);
  CHECK(f[1] == doctest::Approx(0.1));
  // In the fin: through the nearer face.
  CHECK(open_loop.force_N(Vec2{{-45.1e-3, 150e-3}}, Vec2{})[0] == doctest::Approx(-0.03));
  CHECK(open_loop.force_N(Vec2{{-44.9e-3, 150e-3}}, Vec2{})[0] == doctest::Approx(0.03));
  // A corridor: nothing.
  const Vec2 none = open_loop.force_N(Vec2{{-16e-3, 142e-3}}, Vec2{});
  CHECK(none[0] == 0.0);
  CHECK(none[1] == 0.0);
  CHECK(open_loop.faults().empty());
}

}  // namespace hapscene
