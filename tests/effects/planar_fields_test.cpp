// The 2-D penalty fields: spring, damper and texture bands, against their formulas.
#include <doctest/doctest.h>

#include "tests/effects/planar_test_support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;
using namespace hapscene::planar_test;
using hapscene::planar_test::at;  // before a neighbour's at() in its unity batch

TEST_CASE("planar spring: F = -K (x - c) per component") {
  const PlanarSpring spring{.stiffness_N_per_m = 200.0, .center_m = v2(0.01, -0.02)};
  CHECK(spring.force_N(at(0.01, -0.02)) == v2(0.0, 0.0));
  CHECK(spring.force_N(at(0.03, 0.0)) == v2(-200.0 * (0.03 - 0.01), -200.0 * (0.0 + 0.02)));
  CHECK(spring.force_N(at(0.03, 0.0, 5.0, 5.0)) == spring.force_N(at(0.03, 0.0)));  // ignores velocity
  CHECK(spring.open_loop_force_N(at(-0.01, 0.04)) == spring.force_N(at(-0.01, 0.04)));
}

TEST_CASE("planar damper: F = -B v per component") {
  const PlanarDamper damper{.damping_N_s_per_m = 2.0};
  CHECK(damper.force_N(at(0.3, 0.1, 0.1, -0.05)) == v2(-0.2, 2.0 * 0.05));
  CHECK(damper.force_N(at(0.0, 0.0)) == v2(0.0, 0.0));
}

TEST_CASE("planar texture: bands perpendicular to the direction, F = -B v inside") {
  const PlanarTexture texture = parse_as<PlanarTexture>(
      R"({"type": "texture", "width": "5 mm", "spacing": "5 mm", "offset": "1 mm", "damping": 0.5,
          "direction": [3, 4]})");
  CHECK(texture.direction == v2(0.6, 0.8));
  // s = x ux + y uy; bands where (s - 1 mm) mod 10 mm < 5 mm.
  const auto at_s = [&](double s_m, double along_band_m) {
    // A point at s along u, moved along the band (perpendicular to u) by along_band_m.
    return v2(s_m * 0.6 - along_band_m * 0.8, s_m * 0.8 + along_band_m * 0.6);
  };
  CHECK(texture.in_band(at_s(0.002, 0.0)));
  CHECK(texture.in_band(at_s(0.002, 0.037)));  // anywhere along the band
  CHECK_FALSE(texture.in_band(at_s(0.0075, 0.0)));
  CHECK_FALSE(texture.in_band(at_s(0.0005, 0.0)));
  CHECK(texture.in_band(at_s(-0.0065, 0.01)));  // (-7.5 mm) mod 10 mm = 2.5 mm: a band
  CHECK_FALSE(texture.in_band(at_s(-0.002, 0.0)));
  PlanarInput inside = at(0.0, 0.0, 0.1, -0.2);
  inside.x_m = at_s(0.003, 0.02);
  CHECK(texture.force_N(inside) == v2(-0.05, 0.1));
  PlanarInput gap = inside;
  gap.x_m = at_s(0.008, 0.02);
  CHECK(texture.force_N(gap) == v2(0.0, 0.0));
  CHECK(texture.open_loop_force_N(inside) == texture.force_N(inside));
}

TEST_CASE("planar texture: spacing defaults to the width, bands along x with direction [1, 0]") {
  const PlanarTexture texture =
      parse_as<PlanarTexture>(R"({"type": "texture", "width": "2 mm", "damping": 1, "direction": [1, 0]})");
  CHECK(texture.bands.spacing_m == 0.002);
  CHECK(texture.in_band(v2(0.0, 5.0)));
  CHECK_FALSE(texture.in_band(v2(0.002, -3.0)));
  CHECK(texture.in_band(v2(0.004, 0.0)));
}

}  // namespace HAPSCENE_TEST_FILE
