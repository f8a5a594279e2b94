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
