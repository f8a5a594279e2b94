// Effects that can never act are warned about at load, naming the effect and the likely
// cause: a zero gain, a unit slip (a plain number beyond the device's travel), the
// environment's own safety workspace, or a wall on the workspace's edge. "enabled": false
// is the way to leave an effect out silently.
#include <doctest/doctest.h>

#include "engine/harness/validate.hpp"
#include "tests/support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

// The scene's only warning, or a note saying how many there were.
std::string only_warning(const std::string& json_text) {
  const Scene scene = scene_from(json_text);
  if (scene.load_warnings.size() != 1) return std::to_string(scene.load_warnings.size()) + " warnings";
  return scene.load_warnings[0];
}

}  // namespace

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
  // A bare number in a string is metres too.
  CHECK(only_warning(R"({"effects": [{"type": "wall", "position": "20", "stiffness": 500, "solid": "above"}]})")
            .ends_with("did you mean \"20 mm\"?"));
}

TEST_CASE("load: an effect with zero gain warns, naming the effect and its gain") {
  CHECK(only_warning(R"({"effects": [{"type": "spring", "stiffness": 0}]})") ==
        "test.json: /effects/0 (spring): stiffness 0 N/m, so the spring never acts (\"enabled\": false leaves an "
        "effect out without a warning)");
  CHECK(only_warning(R"({"effects": [{"type": "wall", "position": "10 mm", "stiffness": "0 N/mm", "solid": "above"}]})")
            .starts_with("test.json: /effects/0 (wall): stiffness 0 N/m, so the wall never acts"));
  CHECK(only_warning(R"({"effects": [{"type": "damper", "damping": 0}]})")
            .starts_with("test.json: /effects/0 (damper): damping 0 N*s/m, so the damper never acts"));
  CHECK(only_warning(R"({"effects": [{"type": "spring", "stiffness": 100}, {"type": "texture", "width": "5 mm", "damping": 0}]})")
            .starts_with("test.json: /effects/1 (texture): damping 0 N*s/m, so the texture never acts"));
  // One warning per effect: a zero-gain wall beyond the workspace gets the zero-gain one.
  CHECK(only_warning(R"({"effects": [{"type": "wall", "position": 20, "stiffness": 0, "solid": "above"}]})")
            .starts_with("test.json: /effects/0 (wall): stiffness 0 N/m"));
}

TEST_CASE("load: disabled effects and effects that act do not warn") {
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": 20, "stiffness": 500, "solid": "above",
                       "enabled": false}, {"type": "spring", "stiffness": 0, "enabled": false}]})")
            .load_warnings.empty());
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": "20 mm", "stiffness": 500, "solid": "above"}]})")
            .load_warnings.empty());
  // Beyond the workspace on the free side: the solid side covers all of it, so it acts.
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": -20, "stiffness": 500, "solid": "above"}]})")
            .load_warnings.empty());
  // Just inside the edge: it acts over the last micrometre.
  CHECK(scene_from(R"({"effects": [{"type": "wall", "position": "44.999 mm", "stiffness": 500, "solid": "above"}]})")
            .load_warnings.empty());
}

TEST_CASE("load: a wall outside the environment's own safety workspace names it, with no unit hint") {
  // "20 mm" as written, excluded by /safety/workspace: reading it in mm would put it at 20 um.
  const std::string narrowed = R"("safety": {"workspace": ["-10 mm", "10 mm"]})";
  const std::string expected =
      "test.json: /effects/0 (wall): position 0.02 m puts the solid side (above) wholly outside the environment's "
      "safety workspace [-0.01, 0.01] m (/safety/workspace; the device's is [-0.05, 0.045] m), so the wall never acts";
  CHECK(only_warning("{" + narrowed + R"(, "effects": [{"type": "wall", "position": "20 mm", "stiffness": 500,
                     "solid": "above"}]})") == expected);
  // Written as a plain number inside the device's travel: metres, meant as such.
  CHECK(only_warning("{" + narrowed + R"(, "effects": [{"type": "wall", "position": 0.02, "stiffness": 500,
                     "solid": "above"}]})") == expected);
  // A plain number beyond the device's travel still gets its hint, saying the safety
  // workspace would exclude it even in mm.
  CHECK(only_warning("{" + narrowed + R"(, "effects": [{"type": "wall", "position": 20, "stiffness": 500,
                     "solid": "above"}]})")
            .ends_with("so the wall never acts; did you mean \"20 mm\"? (even there it would not act within "
                       "/safety/workspace)"));
  CHECK(only_warning("{" + narrowed + R"(, "effects": [{"type": "wall", "position": -6, "stiffness": 500,
                     "solid": "below"}]})")
            .ends_with("so the wall never acts; did you mean \"-6 mm\"?"));
}

TEST_CASE("load: a wall exactly on the workspace's edge says so, with no unit hint") {
  CHECK(only_warning(R"({"effects": [{"type": "wall", "position": "45 mm", "stiffness": 500, "solid": "above"}]})") ==
        "test.json: /effects/0 (wall): position 0.045 m is the upper edge of the workspace [-0.05, 0.045] m, so its "
        "solid side (above) lies wholly outside it and the wall never acts");
  CHECK(only_warning(R"({"effects": [{"type": "wall", "position": -0.05, "stiffness": 500, "solid": "below"}]})") ==
        "test.json: /effects/0 (wall): position -0.05 m is the lower edge of the workspace [-0.05, 0.045] m, so its "
        "solid side (below) lies wholly outside it and the wall never acts");
  CHECK(only_warning(R"({"safety": {"workspace": ["-10 mm", "10 mm"]}, "effects": [{"type": "wall",
                     "position": "10 mm", "stiffness": 500, "solid": "above"}]})")
            .starts_with("test.json: /effects/0 (wall): position 0.01 m is the upper edge of the environment's safety "
                         "workspace [-0.01, 0.01] m"));
}

TEST_CASE("load: validate fails its scene/effects check for an effect with zero gain") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}, {"type": "damper", "damping": 0}]})");
  const ValidationReport report = validate_scene(scene, {ScenarioKind::hold}, {});
  CHECK_FALSE(report.pass);
  REQUIRE(report.scene_checks.size() == 1);
  CHECK(report.scene_checks[0].name == "effects");
  CHECK(report.scene_checks[0].detail.starts_with("test.json: /effects/1 (damper): damping 0 N*s/m"));
}

TEST_CASE("load: a spring centred beyond the workspace by a plain number warns, hinting mm") {
  // "center": 10 meant as 10 mm: as written, 10 m, where the handle never goes.
  CHECK(only_warning(R"({"effects": [{"type": "spring", "stiffness": 100, "center": 10}]})") ==
        "test.json: /effects/0 (spring): center 10 m lies outside the workspace [-0.05, 0.045] m, so the spring "
        "pulls the handle toward a place it cannot reach; did you mean \"10 mm\"?");
  CHECK(only_warning(R"({"effects": [{"type": "spring", "stiffness": 100, "center": "-3"}]})")
            .ends_with("did you mean \"-3 mm\"?"));
  // Far beyond even in cm: the warning without a hint.
  CHECK(only_warning(R"({"effects": [{"type": "spring", "stiffness": 100, "center": 900}]})")
            .ends_with("toward a place it cannot reach"));
  // With a unit the user meant it; inside the workspace nothing to say.
  CHECK(only_warning(R"({"effects": [{"type": "spring", "stiffness": 100, "center": "10 m"}]})") == "0 warnings");
  CHECK(only_warning(R"({"effects": [{"type": "spring", "stiffness": 100, "center": 0.01}]})") == "0 warnings");
}

}  // namespace HAPSCENE_TEST_FILE
