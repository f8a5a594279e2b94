// The magnet (engine/effects/magnet.hpp), written once over N: its force law in 1-D and
// 2-D, continuous at half the radius and at the rim, zero for a non-finite position, the
// negative gradient of its potential, and loaded from a file in either kind of scene.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "engine/effects/magnet.hpp"
#include "engine/load/environment.hpp"

namespace magnet_test {

using namespace hapscene;

MagnetOf<1> capstan_magnet() {
  MagnetOf<1> magnet;
  magnet.center_m = 0.01;
  magnet.radius_m = 0.004;
  magnet.stiffness_N_per_m = 1000.0;
  return magnet;
}

MagnetOf<2> planar_magnet() {
  MagnetOf<2> magnet;
  magnet.center_m = Vec2{{0.0, 0.12}};
  magnet.radius_m = 0.01;
  magnet.stiffness_N_per_m = 400.0;
  return magnet;
}

template <int N>
Axes<N> force_at(const MagnetOf<N>& magnet, const Axes<N>& x_m) {
  EffectInputOf<N> input;
  input.x_m = x_m;
  return magnet.force_N(input);
}

}  // namespace magnet_test

using namespace magnet_test;

TEST_CASE("magnet: a spring within half the radius, falling to zero at the rim, nothing beyond (1-D)") {
  const MagnetOf<1> magnet = capstan_magnet();
  CHECK(force_at(magnet, 0.01) == 0.0);
  CHECK(force_at(magnet, 0.011) == doctest::Approx(-1.0));         // -K d, d = 1 mm
  CHECK(force_at(magnet, 0.009) == doctest::Approx(1.0));          // pulls back from below too
  CHECK(force_at(magnet, 0.012) == doctest::Approx(-2.0));         // the peak, K r / 2, at d = r/2
  CHECK(force_at(magnet, 0.013) == doctest::Approx(-1.0));         // -K (r - d) beyond r/2
  CHECK(std::fabs(force_at(magnet, 0.014)) < 1e-9);                // the rim
  CHECK(force_at(magnet, 0.05) == 0.0);
  CHECK(force_at(magnet, std::numeric_limits<double>::quiet_NaN()) == 0.0);
  // Continuous at r/2 and at the rim.
  CHECK(force_at(magnet, 0.012 + 1e-12) == doctest::Approx(force_at(magnet, 0.012 - 1e-12)).epsilon(1e-6));
  CHECK(std::fabs(force_at(magnet, 0.014 - 1e-12)) < 1e-6);
}

TEST_CASE("magnet: the same law along the line to the centre in 2-D") {
  const MagnetOf<2> magnet = planar_magnet();
  // 3 mm out along (3, 4) / 5: inside r/2, F = -K d.
  const Vec2 near = force_at(magnet, Vec2{{0.0018, 0.1224}});
  CHECK(near[0] == doctest::Approx(-400.0 * 0.0018));
  CHECK(near[1] == doctest::Approx(-400.0 * 0.0024));
  // 8 mm out along x: F = -K (r - |d|) = -0.8 N along x.
  const Vec2 ring = force_at(magnet, Vec2{{0.008, 0.12}});
  CHECK(ring[0] == doctest::Approx(-0.8));
  CHECK(ring[1] == doctest::Approx(0.0));
  CHECK(force_at(magnet, Vec2{{0.02, 0.12}}) == Vec2{});
  CHECK(force_at(magnet, Vec2{{std::numeric_limits<double>::infinity(), 0.12}}) == Vec2{});
}

TEST_CASE("magnet: its force is the negative gradient of its potential, which is zero at the point") {
  const MagnetOf<2> magnet = planar_magnet();
  CHECK(magnet.potential_J(magnet.center_m) == 0.0);
  constexpr double h = 1e-7;
  for (const double distance_m : {0.001, 0.004, 0.006, 0.009, 0.012}) {
    CAPTURE(distance_m);
    const Vec2 x{{distance_m * 0.6, 0.12 + distance_m * 0.8}};
    const Vec2 force = force_at(magnet, x);
    for (int axis = 0; axis < 2; ++axis) {
      Vec2 up = x, down = x;
      up[axis] += h;
      down[axis] -= h;
      const double gradient = (magnet.potential_J(up) - magnet.potential_J(down)) / (2 * h);
      CHECK(force[axis] == doctest::Approx(-gradient).epsilon(1e-5).scale(1e-9));
    }
  }
  // Beyond the rim it stays at K r^2 / 4.
  CHECK(magnet.potential_J(Vec2{{0.5, 0.5}}) == doctest::Approx(400.0 * 0.01 * 0.01 / 4));
}

TEST_CASE("magnet: acts only when its disc meets the workspace and it has a stiffness") {
  MagnetOf<2> magnet = planar_magnet();
  CHECK(magnet.can_act_within(Vec2{{-0.07, 0.09}}, Vec2{{0.04, 0.165}}));
  CHECK(magnet.can_act_within(Vec2{{0.005, 0.0}}, Vec2{{0.1, 0.2}}));       // 5 mm from the disc's centre
  CHECK_FALSE(magnet.can_act_within(Vec2{{0.011, 0.0}}, Vec2{{0.1, 0.2}}));  // beyond its radius
  magnet.stiffness_N_per_m = 0.0;
  CHECK_FALSE(magnet.can_act_within(Vec2{{-0.07, 0.09}}, Vec2{{0.04, 0.165}}));
  CHECK(capstan_magnet().can_act_within(-0.05, 0.045));
  CHECK_FALSE(capstan_magnet().can_act_within(-0.05, 0.0055));
}

TEST_CASE("magnet: loaded from a file in a 1-D and a 2-D scene, with units") {
  const Environment capstan = compile_environment(
      R"({"effects": [{"type": "magnet", "center": "10 mm", "radius": "4 mm", "stiffness": "1 N/mm"}]})", "magnet.json");
  const auto& one = std::get<MagnetOf<1>>(capstan.scene.effects.at(0));
  CHECK(one.center_m == doctest::Approx(0.01));
  CHECK(one.radius_m == doctest::Approx(0.004));
  CHECK(one.stiffness_N_per_m == doctest::Approx(1000.0));
  const PlanarEnvironment planar = compile_planar_environment(
      R"({"device": "haplink", "effects": [{"type": "magnet", "center": ["0 mm", "120 mm"], "radius": "1 cm", "stiffness": 400}]})",
      "magnet.json");
  const auto& two = std::get<MagnetOf<2>>(planar.scene.effects.at(0));
  CHECK(two.center_m == Vec2{{0.0, 0.12}});
  CHECK(two.radius_m == doctest::Approx(0.01));
}

TEST_CASE("magnet: one whose reach lies wholly beyond the workspace is warned about at load, in 1-D and 2-D") {
  const Environment capstan = compile_environment(
      R"({"effects": [{"type": "magnet", "center": 0.2, "radius": "4 mm", "stiffness": 500}]})", "far.json");
  REQUIRE(capstan.scene.load_warnings.size() == 1);
  CHECK(capstan.scene.load_warnings[0] ==
        "far.json: /effects/0 (magnet): its reach lies wholly outside the workspace [-0.05, 0.045] m, so the magnet "
        "never acts");
  const PlanarEnvironment planar = compile_planar_environment(
      R"({"device": "haplink", "effects": [{"type": "magnet", "center": [0.5, 0.5], "radius": 0.01, "stiffness": 400}]})",
      "far.json");
  REQUIRE(planar.scene.load_warnings.size() == 1);
  CHECK(planar.scene.load_warnings[0].find("(magnet): its reach lies wholly outside the workspace [") != std::string::npos);
  // Within reach: no warning.
  CHECK(compile_environment(R"({"effects": [{"type": "magnet", "center": 0.047, "radius": "4 mm", "stiffness": 500}]})",
                            "near.json")
            .scene.load_warnings.empty());
}
