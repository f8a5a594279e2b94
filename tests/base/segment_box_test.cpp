// One segment-against-box clip for the device's workspace check (the open box: does an
// edge pass through its inside) and the shapes' reach (the closed box: does an edge touch).
#include <doctest/doctest.h>

#include "engine/base/polygon.hpp"

using namespace hapscene;

TEST_CASE("segment and box: through, along a side, through a corner, beside, a point") {
  const Vec2 low{{0.0, 0.0}};
  const Vec2 high{{1.0, 1.0}};
  const auto meets = [&](Vec2 a, Vec2 b, BoxSides sides) { return segment_meets_box(a, b, low, high, sides); };
  // Across the inside: both.
  CHECK(meets({{-1.0, 0.5}}, {{2.0, 0.5}}, BoxSides::closed));
  CHECK(meets({{-1.0, 0.5}}, {{2.0, 0.5}}, BoxSides::open));
  // Along a side, and through a corner only: the closed box, not the open one.
  CHECK(meets({{-1.0, 0.0}}, {{2.0, 0.0}}, BoxSides::closed));
  CHECK_FALSE(meets({{-1.0, 0.0}}, {{2.0, 0.0}}, BoxSides::open));
  CHECK(meets({{0.0, 2.0}}, {{2.0, 0.0}}, BoxSides::closed));   // touches the corner (1, 1)
  CHECK_FALSE(meets({{0.0, 2.0}}, {{2.0, 0.0}}, BoxSides::open));
  // Beside, and ending short of it: neither.
  CHECK_FALSE(meets({{-1.0, 1.5}}, {{2.0, 1.5}}, BoxSides::closed));
  CHECK_FALSE(meets({{-2.0, 0.5}}, {{-0.1, 0.5}}, BoxSides::closed));
  // A point: inside, on a side.
  CHECK(meets({{0.5, 0.5}}, {{0.5, 0.5}}, BoxSides::open));
  CHECK(meets({{1.0, 0.5}}, {{1.0, 0.5}}, BoxSides::closed));
  CHECK_FALSE(meets({{1.0, 0.5}}, {{1.0, 0.5}}, BoxSides::open));
}
