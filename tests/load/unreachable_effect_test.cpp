// Effects that can never act inside the workspace are warned about at load, naming the
// effect and the likely unit; deliberate ones (zero stiffness, "enabled": false) are not.
#include <doctest/doctest.h>

#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

TEST_CASE("load: a wall beyond the workspace warns, naming the effect and hinting mm") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100},
    {"type": "wall", "position": 20, "stiffness": "500 N/m", "solid": "above"}]})");
  REQUIRE(scene.load_warnings.size() == 1);
  CHECK(scene.load_warnings[0] ==
        "test.json: /effects/1 (wall): position 20 m puts the solid side (above) wholly outside the workspace "
        "[-0.05, 0.045] m, so the wall never acts; did you mean \"20 mm\"?");
  // Below, in cm: -6 (m) meant as -6 cm.
  const Scene below = scene_from(R"({"effects": [
    {"type": "wall", "position": -6, "stiffness": "500 N/m", "solid": "below"}]})");
  REQUIRE(below.load_warnings.size() == 1);
  CHECK(below.load_warnings[0].ends_with("did you mean \"-6 mm\"?"));
}

TEST_CASE("load: deliberate no-ops and walls that act do not warn") {
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": 20, "stiffness": 0, "solid": "above"}]})")
            .load_warnings.empty());
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": 20, "stiffness": 500, "solid": "above",
                       "enabled": false}]})")
            .load_warnings.empty());
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": "20 mm", "stiffness": 500, "solid": "above"}]})")
            .load_warnings.empty());
  // Beyond the workspace on the free side: the solid side covers all of it, so it acts.
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": -20, "stiffness": 500, "solid": "above"}]})")
            .load_warnings.empty());
  CHECK(scene_from(R"({"effects": [{"type": "spring", "stiffness": 0}]})").load_warnings.empty());
}
