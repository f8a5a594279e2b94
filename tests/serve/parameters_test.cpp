// The live view's parameters and the in-place edits of environment text behind "save":
// every byte outside the edited value stays; a number over a value written with a unit
// is written in that unit; a missing key is added where its object's members are.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "engine/harness/planar_shape_list.hpp"
#include "engine/load/environment.hpp"
#include "engine/serve/json_text_edit.hpp"
#include "engine/serve/parameters.hpp"
#include "engine/serve/ui_address.hpp"
#include "engine/cli/ui_option.hpp"
#include "tests/support.hpp"

namespace hapscene {

TEST_CASE("json text edit: a value is replaced in place, everything else stays byte for byte") {
  const std::string text = "{\n  \"a\" : [1, {\"b\": \"10 mm\"}],\t\"c\":true }\n";
  CHECK(set_json_value(text, {"a", "1", "b"}, "\"12 mm\"") == "{\n  \"a\" : [1, {\"b\": \"12 mm\"}],\t\"c\":true }\n");
  CHECK(set_json_value(text, {"a", "0"}, "2.5") == "{\n  \"a\" : [2.5, {\"b\": \"10 mm\"}],\t\"c\":true }\n");
  JsonSpan span;
  REQUIRE(find_json_value(text, {"c"}, &span));
  CHECK(text.substr(span.begin, span.end - span.begin) == "true");
  CHECK_FALSE(find_json_value(text, {"d"}, &span));
  // Strings with escapes and brackets inside do not confuse the scanner.
  const std::string tricky = R"({"s": "a\"}], {", "k\"ey": 1, "n": 2})";
  CHECK(set_json_value(tricky, {"n"}, "3") == R"({"s": "a\"}], {", "k\"ey": 1, "n": 3})");
  CHECK(set_json_value(tricky, {"k\"ey"}, "5") == R"({"s": "a\"}], {", "k\"ey": 5, "n": 2})");
}

TEST_CASE("json text edit: a missing member is added after the last one, on its own line when the object spreads over lines") {
  CHECK(set_json_value(R"({"type": "spring", "stiffness": 1})", {"center"}, "0.01") ==
        R"({"type": "spring", "stiffness": 1, "center": 0.01})");
  CHECK(set_json_value("{\n    \"type\": \"script\",\n    \"file\": \"x.lua\"\n}", {"params", "height"}, "0.004") ==
        "{\n    \"type\": \"script\",\n    \"file\": \"x.lua\",\n    \"params\": {\"height\": 0.004}\n}");
  CHECK(set_json_value("{}", {"a"}, "1") == R"({"a": 1})");
  CHECK(test::input_error_of([] { (void)set_json_value("[1]", {"3"}, "1"); }).find("past the array's end") != std::string::npos);
}

TEST_CASE("live parameters: built-in keys with defaults, script parameters, units and ranges from the device") {
  const std::string text = R"({"name": "p", "effects": [
    {"type": "wall", "position": "10 mm", "stiffness": "500 N/m", "solid": "above"},
    {"type": "texture", "width": "5 mm", "damping": 2},
    {"type": "spring", "stiffness": 10, "enabled": false},
    {"type": "script", "file": "../scripts/bumps.lua", "params": {"load": "3 N"}}
  ]})";
  const Scene scene = test::scene_from(text);
  const std::vector<LiveParameter> parameters = live_parameters<1>(nlohmann::json::parse(text), scene);
  std::vector<std::string> names;
  for (const LiveParameter& p : parameters) names.push_back(std::to_string(p.effect) + ":" + p.parameter);
  CHECK(names == std::vector<std::string>{"0:position", "0:stiffness", "1:width", "1:damping", "1:spacing", "1:offset",
                                          "2:stiffness", "2:center", "3:params/bump_at", "3:params/height",
                                          "3:params/load", "3:params/valley_at", "3:params/width"});
  CHECK(parameters[0].value == doctest::Approx(0.010));
  CHECK(parameters[0].min == scene.safety.workspace_min_m);
  CHECK(parameters[0].max == scene.safety.workspace_max_m);
  CHECK(parameters[4].value == doctest::Approx(0.005));  // spacing defaults to the width
  CHECK_FALSE(parameters[4].written);
  CHECK(parameters[10].value == 3.0);
  CHECK(parameters[10].written);
  CHECK(parameters[10].quantity == Quantity::force_N);
  CHECK(parameters[10].min == -scene.safety.max_force_N);

  // A number over "10 mm" is written in mm; a string is written as given; a default is added.
  CHECK(with_parameter(text, parameters, 0, "position", 0.012).find(R"("position": "12 mm")") != std::string::npos);
  CHECK(with_parameter(text, parameters, 0, "stiffness", "0.6 N/mm").find(R"("stiffness": "0.6 N/mm")") != std::string::npos);
  CHECK(with_parameter(text, parameters, 1, "offset", 0.001).find(R"("damping": 2, "offset": 0.001})") != std::string::npos);
  CHECK(with_parameter(text, parameters, 3, "params/height", 0.004).find(R"("params": {"load": "3 N", "height": 0.004})") != std::string::npos);
  CHECK(test::input_error_of([&] { (void)with_parameter(text, parameters, 0, "solid", 1); }) ==
        "/effects/0/solid: no such parameter (GET /api/scene lists them)");
  CHECK(test::input_error_of([&] { (void)with_parameter(text, parameters, 0, "stiffness", nlohmann::json::array()); }) ==
        "value: expected a number (SI) or a string with a unit, got array");
}

TEST_CASE("--ui: PORT, HOST:PORT, or nothing, loopback unless told otherwise") {
  CHECK(parse_ui_address("8080").port == 8080);
  CHECK(parse_ui_address("8080").host == "127.0.0.1");
  CHECK(parse_ui_address("8080").loopback);
  const UiAddress any = parse_ui_address("0.0.0.0:9000");
  CHECK(any.host == "0.0.0.0");
  CHECK(any.port == 9000);
  CHECK_FALSE(any.loopback);
  CHECK(parse_ui_address("[::1]:0").host == "::1");
  CHECK(parse_ui_address("[::1]:0").loopback);
  CHECK(parse_ui_address("localhost:1").loopback);
  CHECK(parse_ui_address("127.1.2.3:1").loopback);
  CHECK(test::input_error_of([] { (void)parse_ui_address("99999"); }) ==
        "--ui: port must be a whole number in [0, 65535], got \"99999\"");
  CHECK(test::input_error_of([] { (void)parse_ui_address("example.com:80"); }) ==
        "--ui: HOST must be a numeric IPv4 or IPv6 address or localhost, got \"example.com\"");

  std::vector<std::string> args{"env.json", "--ui"};
  CHECK(take_ui_option(&args, "hapscene run")->port == 0);
  CHECK(args == std::vector<std::string>{"env.json"});
  args = {"--ui", "env.json", "--quiet"};
  CHECK(take_ui_option(&args, "hapscene run")->port == 0);
  CHECK(args == std::vector<std::string>{"env.json", "--quiet"});
  args = {"--ui", "8081", "env.json"};
  CHECK(take_ui_option(&args, "hapscene run")->port == 8081);
  CHECK(args == std::vector<std::string>{"env.json"});
  args = {"--ui=0.0.0.0:8082", "env.json"};
  CHECK(take_ui_option(&args, "hapscene run")->host == "0.0.0.0");
  args = {"env.json"};
  CHECK_FALSE(take_ui_option(&args, "hapscene run").has_value());
  args = {"--ui", "--ui", "1"};
  CHECK(test::input_error_of([&] { (void)take_ui_option(&args, "hapscene run"); }) == "hapscene run: --ui is given twice");
  args = {"--ui=abc"};
  CHECK(test::input_error_of([&] { (void)take_ui_option(&args, "hapscene run"); }) ==
        "hapscene run: --ui: port must be a whole number in [0, 65535], got \"abc\"");
}

TEST_CASE("live parameters: a 10,000-edge polygon's stiffness range is judged on at most 512 points of its outline") {
  // A disc of radius 15 mm as a 10,000-gon (edges of 9.4 um): each edge judged on its
  // own took 20,000 pose bounds, 16 s before the page was up and again per change.
  constexpr int kEdges = 10000;
  constexpr double kCx = -0.016, kCy = 0.120, kR = 0.015;
  nlohmann::json points = nlohmann::json::array();
  for (int k = 0; k < kEdges; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kEdges;
    points.push_back({kCx + kR * std::cos(a), kCy + kR * std::sin(a)});
  }
  const nlohmann::json document{
      {"name", "polygon"},
      {"device", "haplink"},
      {"effects", {{{"type", "polygon"}, {"points", points}, {"stiffness", "200 N/m"}, {"solid", "inside"}}}}};
  const PlanarScene scene = load_planar_environment_text(document.dump(), "polygon.json");
  const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(scene);
  REQUIRE(shapes.size() == 1);
  const std::vector<Vec2> on = stiffness_bound_points(shapes[0], scene);
  CHECK(on.size() <= 512);
  CHECK(on.size() >= 256);
  // On the outline, and all around it: no gap wider than twice the even spacing.
  double widest_rad = 0.0;
  for (std::size_t i = 0; i < on.size(); ++i) {
    CHECK(std::hypot(on[i][0] - kCx, on[i][1] - kCy) == doctest::Approx(kR).epsilon(1e-5));
    const Vec2& next = on[(i + 1) % on.size()];
    const double gap = std::remainder(std::atan2(next[1] - kCy, next[0] - kCx) - std::atan2(on[i][1] - kCy, on[i][0] - kCx),
                                      2.0 * std::numbers::pi);
    widest_rad = std::max(widest_rad, std::fabs(gap));
  }
  CHECK(widest_rad <= 2.0 * 2.0 * std::numbers::pi / static_cast<double>(on.size()));
  // The range still ends at the lowest bound on the boundary, at a pose on the rim.
  const std::vector<LiveParameter> parameters = live_parameters<2>(document, scene);
  REQUIRE(parameters.size() == 1);
  CHECK(parameters[0].bound_pose);
  CHECK(parameters[0].range_from.find("the lowest on the shape's boundary") != std::string::npos);
  CHECK(std::hypot(parameters[0].bound_at_m[0] - kCx, parameters[0].bound_at_m[1] - kCy) == doctest::Approx(kR).epsilon(1e-4));
}

}  // namespace hapscene
