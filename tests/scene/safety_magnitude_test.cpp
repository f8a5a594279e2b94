// The vector safety stage's magnitude tests: within_magnitude / exceeds_magnitude decide
// exactly as norm(v) <= limit / norm(v) > limit do (the square root is only taken near the
// limit), for vectors at, just inside and just outside the limit and for non-finite ones.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "engine/scene/safety.hpp"

using namespace hapscene;

TEST_CASE("safety: the squared magnitude test decides as the norm does, at the limit to the last bit") {
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  std::uniform_int_distribution<int> ulps(-8, 8);
  int within = 0, outside = 0;
  for (const double limit : {0.001, 0.5, 1.0, 3.0, 4.0, 7.3, 1000.0}) {
    for (int k = 0; k < 4000; ++k) {
      // A vector whose length is the limit give or take a few units in the last place.
      const double a = angle(random);
      double length = limit;
      for (int u = ulps(random); u != 0; u += u > 0 ? -1 : 1) {
        length = std::nextafter(length, u > 0 ? INFINITY : 0.0);
      }
      const Vec2 v{{length * std::cos(a), length * std::sin(a)}};
      CHECK(within_magnitude(v, limit) == (norm(v) <= limit));
      CHECK(exceeds_magnitude(v, limit) == (norm(v) > limit));
      (norm(v) <= limit ? within : outside)++;
      // Far inside and far outside.
      CHECK(within_magnitude(v * 0.5, limit));
      CHECK_FALSE(within_magnitude(v * 2.0, limit));
      CHECK(exceeds_magnitude(v * 2.0, limit));
    }
  }
  CHECK(within > 1000);
  CHECK(outside > 1000);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Vec2& v : {Vec2{{nan, 0.0}}, Vec2{{0.0, inf}}, Vec2{{-inf, inf}}}) {
    CHECK(within_magnitude(v, 5.0) == (norm(v) <= 5.0));
    CHECK(exceeds_magnitude(v, 5.0) == (norm(v) > 5.0));
  }
  CHECK(within_magnitude(Vec2{}, 0.0));
  CHECK_FALSE(exceeds_magnitude(Vec2{}, 0.0));
}

TEST_CASE("safety: a clamped vector is never past the limit, and a huge finite one is clamped, not zeroed") {
  std::mt19937_64 random(29);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  std::uniform_real_distribution<double> exponent(0.0, 300.0);
  for (const double limit : {0.5, 2.0, 3.0, 7.3}) {
    for (int k = 0; k < 20000; ++k) {
      const double a = angle(random);
      const double length = limit * std::pow(10.0, exponent(random));  // from the limit to 1e300 times it
      const Vec2 v{{length * std::cos(a), length * std::sin(a)}};
      const Vec2 limited = limit_magnitude(v, limit);
      CHECK(norm(limited) <= limit);
      CHECK(norm(limited) >= limit * (1.0 - 1e-12));
      // The direction is kept.
      CHECK(std::fabs(limited[0] * v[1] - limited[1] * v[0]) <= 1e-12 * norm(limited) * norm(v));
    }
  }
  // A script's 1e300 N on both axes: 2 N along the diagonal (its squared length overflows).
  const Vec2 huge = limit_magnitude(Vec2{{1e300, 1e300}}, 2.0);
  CHECK(huge[0] == doctest::Approx(std::sqrt(2.0)));
  CHECK(huge[1] == doctest::Approx(std::sqrt(2.0)));
}
