// Axes<N>: the handle state's vector type (engine/base/axes.hpp). One axis is a plain
// double (the 1-DOF tick's registers); two and three axes get the arithmetic effects use.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <type_traits>

#include "engine/base/axes.hpp"

using namespace hapscene;

TEST_CASE("one axis is a double, so the 1-DOF tick is unchanged") {
  static_assert(std::is_same_v<Axes<1>, double>);
  static_assert(sizeof(Axes<2>) == 2 * sizeof(double));
  static_assert(std::is_trivially_copyable_v<Axes<3>>);
  CHECK(dot(-2.0, 3.0) == -6.0);
  CHECK(norm(-2.5) == 2.5);
  CHECK(component(4.0, 0) == 4.0);
}

TEST_CASE("planar vectors: arithmetic, dot, norm and cross") {
  const Vec2 a{{3.0, 4.0}};
  const Vec2 b{{1.0, -2.0}};
  CHECK((a + b) == Vec2{{4.0, 2.0}});
  CHECK((a - b) == Vec2{{2.0, 6.0}});
  CHECK((-a) == Vec2{{-3.0, -4.0}});
  CHECK((2.0 * a) == Vec2{{6.0, 8.0}});
  CHECK((a * 0.5) == Vec2{{1.5, 2.0}});
  CHECK((a / 2.0) == Vec2{{1.5, 2.0}});
  CHECK(dot(a, b) == -5.0);
  CHECK(norm(a) == 5.0);
  CHECK(cross(a, b) == -10.0);
  CHECK(cross(b, a) == 10.0);
  CHECK(a.x() == 3.0);
  CHECK(a.y() == 4.0);
  CHECK(component(a, 1) == 4.0);
}

TEST_CASE("all_finite rejects a NaN or an infinity in any component") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(all_finite(Vec2{{1.0, 2.0}}));
  CHECK_FALSE(all_finite(Vec2{{1.0, nan}}));
  CHECK_FALSE(all_finite(AxisVector<3>{{inf, 0.0, 0.0}}));
  CHECK_FALSE(all_finite(nan));
  CHECK(all_finite(0.0));
}

TEST_CASE("unit_vector and stable_norm keep a vector's direction and length at any scale") {
  // In the normal range: exactly v / norm(v) and norm(v).
  Vec2 unit;
  REQUIRE(unit_vector(Vec2{{3.0, 4.0}}, &unit));
  CHECK(unit == Vec2{{3.0, 4.0}} / norm(Vec2{{3.0, 4.0}}));
  const Vec2 slanted{{0.3, -0.7}};
  REQUIRE(unit_vector(slanted, &unit));
  CHECK(unit == slanted / norm(slanted));
  CHECK(stable_norm(slanted) == norm(slanted));
  // Subnormal components (squares that underflow): the direction of the integers they are
  // multiples of, to the bit (a power of two apart), where v / norm(v) is off or undefined.
  const double ulp = std::numeric_limits<double>::denorm_min();
  const Vec2 tiny{{6072.0 * ulp, 8097.0 * ulp}};
  Vec2 integers;
  REQUIRE(unit_vector(Vec2{{6072.0, 8097.0}}, &integers));
  REQUIRE(unit_vector(tiny, &unit));
  CHECK(unit == integers);
  CHECK(std::fabs(stable_norm(tiny) / (norm(Vec2{{6072.0, 8097.0}}) * ulp) - 1.0) < 1e-15);
  // Squares that are subnormal: 1e-161 squared keeps about 20 steps of the subnormal grid.
  REQUIRE(unit_vector(Vec2{{1e-161, 1e-161}}, &unit));
  CHECK(unit[0] == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  CHECK(unit[1] == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  // Squares that overflow.
  REQUIRE(unit_vector(Vec2{{3e300, 4e300}}, &unit));
  CHECK(unit[0] == doctest::Approx(0.6).epsilon(1e-15));
  CHECK(stable_norm(Vec2{{3e300, 4e300}}) == doctest::Approx(5e300).epsilon(1e-15));
  // No direction: zero, NaN, infinity; *unit untouched.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  unit = Vec2{{7.0, 7.0}};
  CHECK_FALSE(unit_vector(Vec2{}, &unit));
  CHECK_FALSE(unit_vector(Vec2{{nan, 1.0}}, &unit));
  CHECK_FALSE(unit_vector(Vec2{{inf, 1.0}}, &unit));
  CHECK(unit == Vec2{{7.0, 7.0}});
  CHECK(std::isnan(stable_norm(Vec2{{nan, 1.0}})));
}
