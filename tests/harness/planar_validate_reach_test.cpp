// validate's scenarios on a scene whose walls enclose the start (a frame of four walls
// overlapping at the junctions, a pillar standing on the bottom one): the hand keeps to
// the free part it can reach from the start, so the sweep never drags the handle into
// or beyond the frame, and press and swipe leave out the places another wall covers or
// whose point in front is out of reach. (Before, the sweep's raster rows below the frame
// and the presses at the junctions pinned the force at the 2 N limit, and the proxy let
// go of a handle dragged round a wall's end: 2 N to 0 in one tick.)
#include <doctest/doctest.h>

#include <string>

#include "engine/harness/planar_validate.hpp"
#include "engine/load/environment.hpp"

using namespace hapscene;

namespace {

// x in (-58, 28) mm, y in (102, 158) mm is free inside the frame; home is inside it.
const char* kFrame = R"({"name": "frame", "device": "haplink", "effects": [
  {"type": "box", "min": ["-60 mm", "100 mm"], "max": ["30 mm", "102 mm"], "stiffness": "200 N/m", "solid": "inside"},
  {"type": "box", "min": ["-60 mm", "158 mm"], "max": ["30 mm", "160 mm"], "stiffness": "200 N/m", "solid": "inside"},
  {"type": "box", "min": ["-60 mm", "100 mm"], "max": ["-58 mm", "160 mm"], "stiffness": "200 N/m", "solid": "inside"},
  {"type": "box", "min": ["28 mm", "100 mm"], "max": ["30 mm", "160 mm"], "stiffness": "200 N/m", "solid": "inside"},
  {"type": "box", "min": ["10 mm", "101 mm"], "max": ["12 mm", "125 mm"], "stiffness": "200 N/m", "solid": "inside"}]})";

bool inside_frame(const Vec2& p_m) { return p_m[0] > -0.058 && p_m[0] < 0.028 && p_m[1] > 0.102 && p_m[1] < 0.158; }

}  // namespace

TEST_CASE("planar validate reach: the sweep keeps inside walls that enclose the start") {
  const PlanarEnvironment env = compile_planar_environment(kFrame, "frame.json");
  const PlanarValidateScenario sweep = build_planar_validate_scenario(PlanarValidateKind::sweep, env.scene, HarnessOptions{});
  for (const PlanarHandWaypoint& w : sweep.hand.path) {
    CAPTURE(w.p_m[0]);
    CAPTURE(w.p_m[1]);
    CHECK(inside_frame(w.p_m));
  }
  CHECK(sweep.description.find("(within the part the hand reaches from the start: 2 rows left out") != std::string::npos);
}

TEST_CASE("planar validate reach: press leaves out covered and unreachable places, and the frame passes") {
  const PlanarEnvironment env = compile_planar_environment(kFrame, "frame.json");
  const HarnessOptions options;
  const PlanarValidateScenario press = build_planar_validate_scenario(PlanarValidateKind::press, env.scene, options);
  CHECK(press.description.find("places covered by another shape or out of the hand's reach left out") != std::string::npos);
  // The hand's first waypoint off the start is in the free part inside the frame.
  REQUIRE(press.hand.path.size() > 1);
  CHECK(inside_frame(press.hand.path[1].p_m));
  const PlanarValidationReport report = validate_planar_scene(env.scene, {}, options);
  for (const PlanarScenarioResult& s : report.scenarios) {
    for (const CheckResult& c : s.checks) {
      CAPTURE(s.scenario.name);
      CAPTURE(c.name);
      CAPTURE(c.detail);
      CHECK(c.pass);
    }
  }
  CHECK(report.pass);
}
