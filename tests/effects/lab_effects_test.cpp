// The four Hapkit lab effects against their formulas: inside, outside and at the
// boundaries, negative positions, both wall sides, texture fields far from the origin.
#include <doctest/doctest.h>

#include "engine/effects/damper.hpp"
#include "engine/effects/spring.hpp"
#include "engine/effects/texture.hpp"
#include "engine/effects/wall.hpp"

using namespace hapscene;

namespace {
EffectInput at(double x_m, double v_m_per_s = 0.0) {
  EffectInput input;
  input.x_m = x_m;
  input.v_m_per_s = v_m_per_s;
  return input;
}
}  // namespace

TEST_CASE("spring: F = -K (x - x0)") {
  const Spring spring{.stiffness_N_per_m = 100.0, .center_m = 0.01};
  CHECK(spring.force_N(at(0.01)) == 0.0);
  CHECK(spring.force_N(at(0.03)) == -100.0 * (0.03 - 0.01));
  CHECK(spring.force_N(at(-0.02)) == -100.0 * (-0.02 - 0.01));
  CHECK(spring.force_N(at(0.02, 5.0)) == spring.force_N(at(0.02)));  // ignores velocity
}

TEST_CASE("wall: pushes only inside the solid side") {
  const Wall above{.position_m = 0.01, .stiffness_N_per_m = 500.0, .solid_above = true};
  CHECK(above.force_N(at(0.0)) == 0.0);
  CHECK(above.force_N(at(-0.04)) == 0.0);
  CHECK(above.force_N(at(0.01)) == 0.0);  // at the surface: no force, no step
  CHECK(above.force_N(at(0.012)) == -500.0 * (0.012 - 0.01));
  CHECK(above.force_N(at(0.012)) < 0.0);  // pushes back down, out of the wall

  const Wall below{.position_m = -0.01, .stiffness_N_per_m = 500.0, .solid_above = false};
  CHECK(below.force_N(at(0.0)) == 0.0);
  CHECK(below.force_N(at(-0.01)) == 0.0);
  CHECK(below.force_N(at(-0.015)) == -500.0 * (-0.015 + 0.01));
  CHECK(below.force_N(at(-0.015)) > 0.0);  // pushes back up
}

TEST_CASE("damper: F = -B v") {
  const Damper damper{.damping_N_s_per_m = 2.0};
  CHECK(damper.force_N(at(0.0, 0.1)) == -0.2);
  CHECK(damper.force_N(at(-0.03, -0.05)) == 2.0 * 0.05);
  CHECK(damper.force_N(at(0.02, 0.0)) == 0.0);
}

TEST_CASE("texture: damping fields of width w separated by gaps s") {
  Texture texture{.width_m = 0.005, .spacing_m = 0.005, .offset_m = 0.0,
                  .damping_N_s_per_m = 0.5, .period_m = 0.010};
  const double v = 0.1;
  // In a field: F = -B v; in a gap: 0.
  CHECK(texture.force_N(at(0.0025, v)) == -0.05);
  CHECK(texture.force_N(at(0.0075, v)) == 0.0);
  // Edges as written: a field is [x0 + k p, x0 + k p + w).
  CHECK(texture.in_field(0.0));
  CHECK_FALSE(texture.in_field(0.005));
  CHECK(texture.in_field(0.010));
  CHECK_FALSE(texture.in_field(0.015));
  CHECK(texture.in_field(0.020));
  CHECK(texture.in_field(0.0249));
  CHECK_FALSE(texture.in_field(0.025));
  // Negative positions repeat the same pattern: (x - x0) mod p taken in [0, p).
  CHECK(texture.in_field(-0.010));
  CHECK_FALSE(texture.in_field(-0.0025));  // -0.0025 mod 0.01 = 0.0075: a gap
  CHECK(texture.in_field(-0.0075));        // 0.0025: a field
  CHECK(texture.force_N(at(-0.0075, -v)) == 0.05);
  // Far from the origin: the same, at constant cost.
  CHECK(texture.in_field(1000.0025));
  CHECK_FALSE(texture.in_field(1000.0075));
  CHECK(texture.in_field(-1000.0075));
  // Without velocity nothing happens even in a field.
  CHECK(texture.force_N(at(0.0025, 0.0)) == 0.0);
}

TEST_CASE("texture: spacing and offset shift the fields") {
  const Texture texture{.width_m = 0.002, .spacing_m = 0.008, .offset_m = 0.001,
                        .damping_N_s_per_m = 1.0, .period_m = 0.010};
  CHECK_FALSE(texture.in_field(0.0));
  CHECK(texture.in_field(0.001));
  CHECK(texture.in_field(0.0029));
  CHECK_FALSE(texture.in_field(0.003));
  CHECK(texture.in_field(0.011));
  CHECK(texture.in_field(-0.009));
  CHECK_FALSE(texture.in_field(-0.0095));
}
