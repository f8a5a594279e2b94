// 2-D effects that can never act are warned about at load as 1-D ones are (the same
// mechanism: can_act_within on the workspace, then a message naming the effect): a zero
// gain, a solid shape or a wall's half-plane wholly outside the workspace box, a cage the
// workspace lies wholly inside. They stay listed and are not compiled; validate fails its
// scene/effects check on them.
#include <doctest/doctest.h>

#include <string>

#include "engine/harness/planar_validate.hpp"
#include "engine/load/environment.hpp"

using namespace hapscene;

namespace {

// The Haplink's workspace box is [-70, 40] x [90, 165] mm.
PlanarScene planar_from(const std::string& effects, const std::string& extra = "") {
  return load_planar_environment_text(R"({"device": "haplink", )" + extra + R"("effects": [)" + effects + "]}",
                                      "test.json");
}

std::string only_warning(const std::string& effects, const std::string& extra = "") {
  const PlanarScene scene = planar_from(effects, extra);
  if (scene.load_warnings.size() != 1) return std::to_string(scene.load_warnings.size()) + " warnings";
  return scene.load_warnings[0];
}

}  // namespace

TEST_CASE("planar load: effects with zero gain warn, naming the effect and its gain") {
  CHECK(only_warning(R"({"type": "spring", "stiffness": 0, "center": [0, 0.12]})") ==
        "test.json: /effects/0 (spring): stiffness 0 N/m, so the spring never acts (\"enabled\": false leaves an "
        "effect out without a warning)");
  CHECK(only_warning(R"({"type": "damper", "damping": 1}, {"type": "damper", "damping": 0})")
            .starts_with("test.json: /effects/1 (damper): damping 0 N*s/m, so the damper never acts"));
  CHECK(only_warning(R"({"type": "texture", "width": "2 mm", "spacing": "2 mm", "offset": 0, "damping": 0,
                        "direction": [1, 0]})")
            .starts_with("test.json: /effects/0 (texture): damping 0 N*s/m, so the texture never acts"));
  CHECK(only_warning(R"({"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 0,
                        "solid": "inside"})")
            .starts_with("test.json: /effects/0 (box): stiffness 0 N/m, so the box never acts"));
  CHECK(only_warning(R"({"type": "circle", "center": ["-15 mm", "130 mm"], "radius": "10 mm", "stiffness": 0,
                        "solid": "outside"})")
            .starts_with("test.json: /effects/0 (circle): stiffness 0 N/m"));
  CHECK(only_warning(R"({"type": "wall", "point": [0, 0.12], "normal": [0, 1], "stiffness": 0})")
            .starts_with("test.json: /effects/0 (wall): stiffness 0 N/m"));
  CHECK(only_warning(R"({"type": "polygon", "points": [[0, 0.1], [0.01, 0.1], [0, 0.11]], "stiffness": 0,
                        "solid": "inside"})")
            .starts_with("test.json: /effects/0 (polygon): stiffness 0 N/m"));
}

TEST_CASE("planar load: shapes whose solid lies outside the workspace warn and are not compiled") {
  // A solid disc in metres where millimetres were meant.
  const PlanarScene scene = planar_from(R"({"type": "spring", "stiffness": 10, "center": [0, 0.12]},
      {"type": "circle", "center": [-15, 130], "radius": 10, "stiffness": 200, "solid": "inside"})");
  REQUIRE(scene.load_warnings.size() == 1);
  CHECK(scene.load_warnings[0] ==
        "test.json: /effects/1 (circle): the solid disc of radius 10 m about (-15, 130) m lies wholly outside the "
        "workspace [-0.07, 0.04] x [0.09, 0.165] m, so the circle never acts; did you mean \"center\": "
        "[\"-15 mm\", \"130 mm\"], \"radius\": \"10 mm\"?");
  CHECK(scene.effects.size() == 2);                                   // still listed
  CHECK(scene.bank.group<PlanarCircle>().empty());                    // not compiled
  CHECK(scene.bank.proxy_count() == 0);
  CHECK(only_warning(R"({"type": "box", "min": ["50 mm", "100 mm"], "max": ["60 mm", "120 mm"], "stiffness": 200,
                        "solid": "inside"})") ==
        "test.json: /effects/0 (box): the solid box [0.05, 0.06] x [0.1, 0.12] m lies wholly outside the workspace "
        "[-0.07, 0.04] x [0.09, 0.165] m, so the box never acts");
  CHECK(only_warning(R"({"type": "polygon", "points": [["50 mm", "100 mm"], ["60 mm", "100 mm"], ["55 mm", "110 mm"]],
                        "stiffness": 200, "solid": "inside"})") ==
        "test.json: /effects/0 (polygon): the solid polygon of 3 points lies wholly outside the workspace "
        "[-0.07, 0.04] x [0.09, 0.165] m, so the polygon never acts");
  // A wall whose solid side (away from its normal) is below the workspace.
  CHECK(only_warning(R"({"type": "wall", "point": ["0 mm", "80 mm"], "normal": [0, 1], "stiffness": 200})") ==
        "test.json: /effects/0 (wall): its solid half-plane (the side of the line through (0, 0.08) m away from the "
        "normal (0, 1)) does not meet the workspace [-0.07, 0.04] x [0.09, 0.165] m, so the wall never acts");
  // Cages the workspace lies wholly inside.
  CHECK(only_warning(R"({"type": "box", "min": ["-80 mm", "80 mm"], "max": ["50 mm", "170 mm"], "stiffness": 200,
                        "solid": "outside"})") ==
        "test.json: /effects/0 (box): the workspace [-0.07, 0.04] x [0.09, 0.165] m lies wholly inside the box's "
        "free part (\"solid\": \"outside\"), so the box never acts");
  CHECK(only_warning(R"({"type": "circle", "center": ["-15 mm", "127 mm"], "radius": "200 mm", "stiffness": 200,
                        "solid": "outside"})")
            .starts_with("test.json: /effects/0 (circle): the workspace "));
  CHECK(only_warning(R"({"type": "polygon", "points": [[-1, 0], [1, 0], [0, 1]], "stiffness": 200,
                        "solid": "outside"})")
            .starts_with("test.json: /effects/0 (polygon): the workspace "));
}

TEST_CASE("planar load: a shape's lengths written without a unit get the unit hint, as a 1-D wall's position") {
  // Each shape's unitless lengths, read in mm, would put it across the workspace.
  CHECK(only_warning(R"({"type": "box", "min": [-40, 110], "max": [0, 135], "stiffness": 200, "solid": "inside"})") ==
        "test.json: /effects/0 (box): the solid box [-40, 0] x [110, 135] m lies wholly outside the workspace "
        "[-0.07, 0.04] x [0.09, 0.165] m, so the box never acts; did you mean \"min\": [\"-40 mm\", \"110 mm\"], "
        "\"max\": [\"0 mm\", \"135 mm\"]?");
  CHECK(only_warning(R"({"type": "wall", "point": ["0", "150"], "normal": [0, -1], "stiffness": 200})")
            .ends_with("so the wall never acts; did you mean \"point\": [\"0 mm\", \"150 mm\"]?"));
  CHECK(only_warning(R"({"type": "polygon", "points": [[-40, 110], [0, 110], [0, 135], [-40, 135]], "stiffness": 200,
                        "solid": "inside"})")
            .ends_with("did you mean \"points\": [[\"-40 mm\", \"110 mm\"], [\"0 mm\", \"110 mm\"], ...]?"));
  // In cm: 1.5 (m) meant as 1.5 cm... a disc of radius 2 cm about (-1.5, 13) cm.
  CHECK(only_warning(R"({"type": "circle", "center": [-1.5, 13], "radius": 2, "stiffness": 200, "solid": "inside"})")
            .ends_with("did you mean \"center\": [\"-1.5 cm\", \"13 cm\"], \"radius\": \"2 cm\"?"));
  // Only the lengths written without a unit are read again: the radius here has one.
  CHECK(only_warning(R"({"type": "circle", "center": [-15, 127], "radius": "10 mm", "stiffness": 200, "solid": "inside"})")
            .ends_with("did you mean \"center\": [\"-15 mm\", \"127 mm\"]?"));
  // Within the device's workspace but outside the environment's own: noted.
  CHECK(only_warning(R"({"type": "box", "min": [20, 100], "max": [30, 120], "stiffness": 200, "solid": "inside"})",
                     R"("safety": {"workspace": {"min": ["-40 mm", "100 mm"], "max": ["0 mm", "140 mm"]}}, )")
            .ends_with("did you mean \"min\": [\"20 mm\", \"100 mm\"], \"max\": [\"30 mm\", \"120 mm\"]? (even there "
                       "it would not act within /safety/workspace)"));
  // No hint: lengths with units, numbers that read in mm or cm still miss the device, and
  // a cage that read in mm would shrink round nothing.
  CHECK(only_warning(R"({"type": "box", "min": ["50 mm", "100 mm"], "max": ["60 mm", "120 mm"], "stiffness": 200,
                        "solid": "inside"})").find("did you mean") == std::string::npos);
  CHECK(only_warning(R"({"type": "box", "min": [500, 100], "max": [600, 120], "stiffness": 200, "solid": "inside"})")
            .find("did you mean") == std::string::npos);
  CHECK(only_warning(R"({"type": "polygon", "points": [[-1, 0], [1, 0], [0, 1]], "stiffness": 200, "solid": "outside"})")
            .find("did you mean") == std::string::npos);
}

TEST_CASE("planar load: the environment's own safety workspace is named") {
  CHECK(only_warning(R"({"type": "box", "min": ["20 mm", "100 mm"], "max": ["30 mm", "120 mm"], "stiffness": 200,
                        "solid": "inside"})",
                     R"("safety": {"workspace": {"min": ["-40 mm", "100 mm"], "max": ["0 mm", "140 mm"]}}, )") ==
        "test.json: /effects/0 (box): the solid box [0.02, 0.03] x [0.1, 0.12] m lies wholly outside the "
        "environment's safety workspace [-0.04, 0] x [0.1, 0.14] m (/safety/workspace; the device's is "
        "[-0.07, 0.04] x [0.09, 0.165] m), so the box never acts");
}

TEST_CASE("planar load: shapes that reach the workspace do not warn") {
  const char* acting[] = {
      // Overlapping the workspace's edge, or crossing it with no vertex inside.
      R"({"type": "box", "min": ["30 mm", "100 mm"], "max": ["60 mm", "120 mm"], "stiffness": 200, "solid": "inside"})",
      R"({"type": "polygon", "points": [["-100 mm", "100 mm"], ["100 mm", "100 mm"], ["0 mm", "101 mm"]],
          "stiffness": 200, "solid": "inside"})",
      // A polygon holding the whole workspace (solid inside).
      R"({"type": "polygon", "points": [[-1, 0], [1, 0], [0, 1]], "stiffness": 200, "solid": "inside"})",
      R"({"type": "circle", "center": ["50 mm", "127 mm"], "radius": "11 mm", "stiffness": 200, "solid": "inside"})",
      // Cages that leave part of the workspace solid.
      R"({"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "outside"})",
      R"({"type": "polygon", "points": [["-40 mm", "110 mm"], ["0 mm", "110 mm"], ["0 mm", "135 mm"]],
          "stiffness": 200, "solid": "outside"})",
      // A wall whose solid side holds only a corner of the workspace.
      R"({"type": "wall", "point": ["39 mm", "164 mm"], "normal": [-1, -1], "stiffness": 200})",
  };
  for (const char* effect : acting) {
    CAPTURE(effect);
    const PlanarScene scene = planar_from(effect);
    CHECK(scene.load_warnings.empty());
    CHECK(scene.bank.proxy_count() == 1);
  }
}

TEST_CASE("planar validate: an effect that never acts fails scene/effects") {
  const PlanarScene scene = planar_from(R"({"type": "damper", "damping": 0})");
  const PlanarValidationReport report = validate_planar_scene(scene, {PlanarValidateKind::hold}, {});
  CHECK_FALSE(report.pass);
  REQUIRE_FALSE(report.scene_checks.empty());
  CHECK(report.scene_checks[0].name == "effects");
  CHECK(report.scene_checks[0].detail.starts_with("test.json: /effects/0 (damper): damping 0 N*s/m"));
}

TEST_CASE("planar load: a spring centred beyond the workspace by plain numbers warns, hinting mm") {
  CHECK(only_warning(R"({"type": "spring", "stiffness": 100, "center": [-10, 120]})") ==
        "test.json: /effects/0 (spring): center (-10, 120) m lies outside the box round the workspace "
        "[-0.07, 0.04] x [0.09, 0.165] m, so the spring pulls the handle toward a place it cannot reach; did you "
        "mean \"center\": [\"-10 mm\", \"120 mm\"]?");
  CHECK(only_warning(R"({"type": "spring", "stiffness": 100, "center": ["-10 mm", "120 mm"]})") == "0 warnings");
}
