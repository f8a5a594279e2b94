// Parsing the 2-D effects: vectors with units, defaults, "enabled", and the located
// errors for bad input (ranges, unknown keys, 1-D forms, degenerate shapes).
#include <doctest/doctest.h>

#include <cmath>

#include "tests/effects/planar_test_support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;
using namespace hapscene::planar_test;
using hapscene::planar_test::at;  // before a neighbour's at() in its unity batch

TEST_CASE("planar parse: vectors in m or unit strings, defaults") {
  const PlanarSpring spring = parse_as<PlanarSpring>(R"({"type": "spring", "stiffness": "0.2 N/mm", "center": ["10 mm", 0.14]})");
  CHECK(spring.stiffness_N_per_m == 200.0);
  CHECK(spring.center_m == v2(0.01, 0.14));
  CHECK(parse_as<PlanarSpring>(R"({"type": "spring", "stiffness": 100})").center_m == v2(0.0, 0.0));
  const PlanarBox box = parse_as<PlanarBox>(
      R"({"type": "box", "min": ["-20 mm", "100 mm"], "max": ["20 mm", "140 mm"], "stiffness": 400, "solid": "outside"})");
  CHECK(box.min_m == v2(-0.02, 0.1));
  CHECK(box.max_m == v2(0.02, 0.14));
  CHECK_FALSE(box.solid_inside);
  CHECK(box.outline.edge_count() == 4);
  const PlanarPolygon polygon = parse_as<PlanarPolygon>(
      R"({"type": "polygon", "points": [[0, 0], ["30 mm", 0], [0, "30 mm"]], "stiffness": 500, "solid": "inside",
          "friction": {"static": 0.4, "dynamic": 0.2}})");
  CHECK(polygon.outline.edge_count() == 3);
  CHECK(polygon.friction.static_mu == 0.4);
  CHECK(polygon.friction.dynamic_mu == 0.2);
  CHECK_FALSE(parse_as<PlanarPolygon>(
                  R"({"type": "polygon", "points": [[0, 0], [1, 0], [0, 1]], "stiffness": 1, "solid": "inside"})")
                  .friction.any());
  const PlanarDamper damper = parse_as<PlanarDamper>(R"({"type": "damper", "damping": "2 N*s/m", "enabled": true})");
  CHECK(damper.damping_N_s_per_m == 2.0);
}

TEST_CASE("planar parse: enabled false leaves the effect out unread") {
  PlanarEffect effect;
  CHECK_FALSE(parse_planar_effect(nlohmann::json::parse(R"({"type": "box", "enabled": false, "min": "junk"})"),
                                  "/effects/0", "env.json", &effect));
  CHECK(parse_error(R"({"type": "damper", "damping": 1, "enabled": "yes"})") ==
        "env.json: /effects/2/enabled: expected a boolean, got string");
}

TEST_CASE("planar parse: located errors") {
  // Unknown types and keys, with suggestions.
  CHECK(parse_error(R"({"type": "cirle", "center": [0, 0], "radius": 1, "stiffness": 1, "solid": "inside"})") ==
        "env.json: /effects/2/type: unknown 2-D effect type \"cirle\" (did you mean \"circle\"?)");
  CHECK(parse_error(R"({"type": "spring", "stiffness": 1, "centre": [0, 0]})") ==
        "env.json: /effects/2/centre: unknown key \"centre\" (did you mean \"center\"?)");
  CHECK(parse_error(R"({"type": "texture", "width": 0.001, "damping": 1, "direction": [1, 0], "mirror": true})") ==
        "env.json: /effects/2/mirror: unknown key \"mirror\"");
  // Missing keys.
  CHECK(parse_error(R"({"type": "circle", "center": [0, 0], "stiffness": 1, "solid": "inside"})") ==
        "env.json: /effects/2: missing required key \"radius\"");
  CHECK(parse_error(R"({"type": "box", "min": [0, 0], "max": [1, 1], "stiffness": 1})") ==
        "env.json: /effects/2: missing required key \"solid\"");
  // Vectors: their form, each component's unit and range.
  CHECK(parse_error(R"({"type": "spring", "stiffness": 1, "center": 0.01})") ==
        "env.json: /effects/2/center: expected a 2-D vector [x, y] of lengths in m (or strings with a unit), "
        "got number (a 1-D form: a 2-D scene takes [x, y])");
  CHECK(parse_error(R"({"type": "spring", "stiffness": 1, "center": [0, 1, 2]})") ==
        "env.json: /effects/2/center: expected a 2-D vector [x, y] of lengths in m (or strings with a unit), "
        "got an array of 3");
  CHECK(parse_error(R"({"type": "spring", "stiffness": 1, "center": ["10 mm", "2 N"]})") ==
        "env.json: /effects/2/center/1: expected a length (m), got a force (\"2 N\")");
  CHECK(parse_error(R"({"type": "spring", "stiffness": 1, "center": [0, 5000]})") ==
        "env.json: /effects/2/center/1: must be in [-1000, 1000] m, got 5000 m");
  CHECK(parse_error(R"({"type": "spring", "stiffness": -1})") == "env.json: /effects/2/stiffness: must be >= 0, got -1 N/m");
  CHECK(parse_error(R"({"type": "polygon", "points": [[0, 0], [1, 0], [0, "x"]], "stiffness": 1, "solid": "inside"})")
            .starts_with("env.json: /effects/2/points/2/1: "));
  // Degenerate shapes.
  CHECK(parse_error(R"({"type": "wall", "point": [0, 0], "normal": [0, 0], "stiffness": 1})") ==
        "env.json: /effects/2/normal: must not be the zero vector: it gives the direction");
  CHECK(parse_error(R"({"type": "texture", "width": 0.001, "damping": 1, "direction": [0, 0]})") ==
        "env.json: /effects/2/direction: must not be the zero vector: it gives the direction");
  // Components too small for their squares still give their direction (unit_vector): a
  // normal of [1e-161, 1e-161] came out 0.6 % long (the wall 1.2 % stiff), one of
  // [1e-310, 0] was refused as zero.
  const PlanarWall tiny = parse_as<PlanarWall>(R"({"type": "wall", "point": [0, 0], "normal": [1e-161, 1e-161], "stiffness": 1})");
  CHECK(tiny.normal[0] == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  CHECK(tiny.normal[1] == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
  CHECK(parse_as<PlanarWall>(R"({"type": "wall", "point": [0, 0], "normal": [1e-310, 0], "stiffness": 1})").normal ==
        v2(1.0, 0.0));
  CHECK(parse_as<PlanarTexture>(R"({"type": "texture", "width": 0.001, "damping": 1, "direction": [0, -3e-320]})")
            .direction == v2(0.0, -1.0));
  CHECK(parse_error(R"({"type": "box", "min": [0, 0.02], "max": [0.01, 0.02], "stiffness": 1, "solid": "inside"})") ==
        "env.json: /effects/2/max: must be above \"min\" in y, got min 0.02 m and max 0.02 m");
  CHECK(parse_error(R"({"type": "box", "min": [0.03, 0], "max": [0.01, 0.02], "stiffness": 1, "solid": "inside"})") ==
        "env.json: /effects/2/max: must be above \"min\" in x, got min 0.03 m and max 0.01 m");
  CHECK(parse_error(R"({"type": "circle", "center": [0, 0], "radius": 0, "stiffness": 1, "solid": "inside"})") ==
        "env.json: /effects/2/radius: must be > 0, got 0 m");
  CHECK(parse_error(R"({"type": "circle", "center": [0, 0], "radius": 0.01, "stiffness": 1, "solid": "in"})") ==
        "env.json: /effects/2/solid: \"in\" is not one of \"inside\", \"outside\"");
  // Polygons.
  const auto polygon = [](const std::string& points) {
    return parse_error(R"({"type": "polygon", "stiffness": 1, "solid": "inside", "points": )" + points + "}");
  };
  CHECK(polygon("[[0, 0], [1, 0]]") == "env.json: /effects/2/points: expected 3 to 10000 points, got 2");
  CHECK(polygon("[[0, 0], [1, 0], [1, 0], [0, 1]]") == "env.json: /effects/2/points: points 1 and 2 coincide");
  CHECK(polygon("[[0, 0], [1, 0], [0, 1], [0, 0]]") ==
        "env.json: /effects/2/points: points 3 and 0 coincide: the outline closes by itself, leave out the last point");
  CHECK(polygon("[[0, 0], [1, 1], [2, 2]]") ==
        "env.json: /effects/2/points: edges 1 and 2 fold back on each other at point 2");
  CHECK(polygon("[[0, 0], [1, 0], [2, 0], [3, 0]]") ==
        "env.json: /effects/2/points: edges 2 and 3 fold back on each other at point 3");
  CHECK(polygon("[[0, 0], [1, 1], [1, 0], [0, 1]]") ==
        "env.json: /effects/2/points: edges 0 (points 0 to 1) and 2 (points 2 to 3) cross or touch: "
        "the outline must not intersect itself");
  // A vertex touching another edge.
  CHECK(polygon("[[0, 0], [2, 0], [2, 2], [1, 0], [0, 2]]").find("cross or touch") != std::string::npos);
  CHECK(polygon(R"({"x": 1})") == "env.json: /effects/2/points: expected an array of points [[x, y], ...], got object");
  // Friction.
  const auto friction = [](const std::string& block) {
    return parse_error(R"({"type": "polygon", "stiffness": 1, "solid": "inside", "points": [[0, 0], [1, 0], [0, 1]],
                           "friction": )" + block + "}");
  };
  CHECK(friction(R"({"static": 0.2, "dynamic": 0.3})") ==
        "env.json: /effects/2/friction/dynamic: must not exceed the static coefficient (0.2), got 0.3");
  CHECK(friction(R"({"static": 0.2})") == "env.json: /effects/2/friction: missing required key \"dynamic\"");
  CHECK(friction(R"({"static": 0.2, "dynamic": 0.1, "viscous": 1})") ==
        "env.json: /effects/2/friction/viscous: unknown key \"viscous\"");
  CHECK(friction(R"({"static": -0.2, "dynamic": 0.1})") == "env.json: /effects/2/friction/static: must be >= 0, got -0.2");
  CHECK(friction("0.3") == "env.json: /effects/2/friction: expected an object, got number");
  // The 1-D wall's keys in a 2-D scene.
  CHECK(parse_error(R"({"type": "wall", "position": 0.01, "stiffness": 1, "solid": "above"})") ==
        "env.json: /effects/2/position: is a key of the 1-D wall: a 2-D wall takes \"point\": [x, y] and "
        "\"normal\": [nx, ny]");
  CHECK(parse_error(R"({"type": "wall", "point": [0, 0], "normal": [0, 1], "stiffness": 1, "solid": "above"})") ==
        "env.json: /effects/2/solid: is a key of the 1-D wall: a 2-D wall is solid on the side its normal points away from");
}

TEST_CASE("planar effect types: the table, the bank and its proxies") {
  std::vector<std::string_view> names;
  for (const PlanarEffectType& type : planar_effect_types()) names.push_back(type.name);
  CHECK(names ==
        std::vector<std::string_view>{"spring", "wall", "box", "circle", "polygon", "damper", "texture", "magnet", "script"});

  PlanarEffectBank bank;
  PlanarBuiltInEffects::add(bank, parse_effect(R"({"type": "spring", "stiffness": 100, "center": [0, 0.12]})"));
  PlanarBuiltInEffects::add(bank, parse_effect(
      R"({"type": "box", "min": [-0.02, 0.1], "max": [0.02, 0.14], "stiffness": 400, "solid": "inside"})"));
  PlanarBuiltInEffects::add(bank, parse_effect(
      R"({"type": "circle", "center": [0.05, 0.12], "radius": 0.01, "stiffness": 300, "solid": "inside"})"));
  PlanarBuiltInEffects::add(bank, parse_effect(R"({"type": "damper", "damping": 1})"));
  CHECK(bank.proxy_count() == 2);
  std::vector<PlanarProxyState> proxies(bank.proxy_count());
  // Outside both shapes: spring and damper only.
  const PlanarInput outside = at(0.0, 0.09, 0.1, 0.0);
  CHECK(bank.force_N(outside, proxies) == v2(-100.0 * 0.0 - 0.1, -100.0 * (0.09 - 0.12) + 0.0));
  // Pressed 1 mm into the box from below: the box's proxy on its bottom.
  const PlanarInput pressed = at(0.0, 0.101);
  const Vec2 closed = bank.force_N(pressed, proxies);
  CHECK(proxies[0].contact == ProxyContact::edge);
  CHECK(proxies[1].contact == ProxyContact::none);
  CHECK(closed[1] == doctest::Approx(-100.0 * (0.101 - 0.12) + 400.0 * -0.001));
  CHECK(closed == bank.open_loop_force_N(pressed));
}

}  // namespace HAPSCENE_TEST_FILE
