// A 2-D script's optional `shapes` (docs/reference/lua.md, "Scripts in 2-D"): boxes and
// circles in SI or unit strings, read at load into ScriptProgram::shapes; every bad entry
// is a load error naming it (shapes[i].key); a 1-D scene refuses a script that declares
// shapes, after its own dimension check.
#include <doctest/doctest.h>

#include <string>

#include "engine/base/errors.hpp"
#include "tests/lua/script_test_support.hpp"

using namespace hapscene;
using namespace hapscene::test;

namespace {

const char* kForce2 = "function force(s) return 0, 0 end\n";

ScriptProgram compile_planar(const std::string& source) {
  return compile_script("t.lua", source, nlohmann::json::object(), "env.json", "/effects/0/params", {}, 2);
}

// The load error of a 2-D script whose `shapes` is `shapes`, or "".
std::string shapes_error(const std::string& shapes) {
  try {
    compile_planar("shapes = " + shapes + "\n" + kForce2);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("script shapes: boxes and circles in SI or unit strings, in order") {
  const ScriptProgram p = compile_planar(
      "params = { r = \"15 mm\" }\n"
      "shapes = { { type = \"box\", min = { -0.04, \"110 mm\" }, max = { \"0 mm\", 0.135 }, solid = \"inside\" },\n"
      "           { type = \"circle\", center = { \"-16 mm\", \"12 cm\" }, radius = params.r, solid = \"outside\" } }\n" +
      std::string(kForce2));
  REQUIRE(p.shapes.size() == 2);
  const ScriptShape& box = p.shapes[0];
  CHECK(box.kind == ScriptShape::Kind::box);
  CHECK(box.solid_inside);
  CHECK(box.min_m[0] == -0.04);
  CHECK(box.min_m[1] == doctest::Approx(0.110).epsilon(1e-12));
  CHECK(box.max_m[0] == 0.0);
  CHECK(box.max_m[1] == 0.135);
  const ScriptShape& circle = p.shapes[1];
  CHECK(circle.kind == ScriptShape::Kind::circle);
  CHECK_FALSE(circle.solid_inside);
  CHECK(circle.center_m[0] == doctest::Approx(-0.016).epsilon(1e-12));
  CHECK(circle.center_m[1] == doctest::Approx(0.12).epsilon(1e-12));
  CHECK(circle.radius_m == doctest::Approx(0.015).epsilon(1e-12));
  // None declared, or an empty list: no shapes.
  CHECK(compile_planar(kForce2).shapes.empty());
  CHECK(compile_planar(std::string("shapes = {}\n") + kForce2).shapes.empty());
}

TEST_CASE("script shapes: the shipped box, circle and maze declare what they render") {
  for (const char* solid : {"inside", "outside"}) {
    CAPTURE(solid);
    const nlohmann::json overrides = {{"solid", solid}};
    const ScriptProgram box = compile_script("scripts/planar/box.lua", read_script("planar/box.lua"), overrides,
                                             "env.json", "/effects/0/params", {}, 2);
    REQUIRE(box.shapes.size() == 1);
    CHECK(box.shapes[0].kind == ScriptShape::Kind::box);
    CHECK(box.shapes[0].solid_inside == (std::string(solid) == "inside"));
    CHECK(box.shapes[0].min_m[0] == doctest::Approx(-0.040));
    CHECK(box.shapes[0].max_m[1] == doctest::Approx(0.135));
    const ScriptProgram circle = compile_script("scripts/planar/circle.lua", read_script("planar/circle.lua"),
                                                overrides, "env.json", "/effects/0/params", {}, 2);
    REQUIRE(circle.shapes.size() == 1);
    CHECK(circle.shapes[0].kind == ScriptShape::Kind::circle);
    CHECK(circle.shapes[0].solid_inside == (std::string(solid) == "inside"));
    CHECK(circle.shapes[0].radius_m == doctest::Approx(0.015));
  }
  const ScriptProgram maze = compile_script("scripts/planar/maze.lua", read_script("planar/maze.lua"),
                                            nlohmann::json::object(), "env.json", "/effects/0/params", {}, 2);
  CHECK(maze.shapes.size() == 9);
}

TEST_CASE("script shapes: a bad entry is a load error naming it") {
  CHECK(shapes_error("3") == "t.lua: shapes must be a list such as { {type = \"box\", min = {x, y}, max = {x, y}, "
                             "solid = \"inside\"} or {type = \"circle\", center = {x, y}, radius = r, solid = "
                             "\"outside\"} }, got a number");
  CHECK(shapes_error("{ box = {} }").find("t.lua: shapes must be a list { shape, shape, ... }") == 0);
  CHECK(shapes_error("{ 5 }").find("t.lua: shapes[1]: expected a table such as") == 0);
  CHECK(shapes_error("{ { min = {0, 0}, max = {1, 1}, solid = \"inside\" } }") ==
        "t.lua: shapes[1].type: expected \"box\" or \"circle\", got a nil");
  CHECK(shapes_error("{ { type = \"square\" } }") == "t.lua: shapes[1].type: expected \"box\" or \"circle\", got \"square\"");
  CHECK(shapes_error("{ { type = \"box\", min = {0, 0}, max = {1, 1}, solid = \"inside\", radius = 1 } }") ==
        "t.lua: shapes[1].radius: not a key of a box (it takes type, min, max, solid)");
  CHECK(shapes_error("{ { type = \"circle\", centre = {0, 0}, radius = 1, solid = \"inside\" } }") ==
        "t.lua: shapes[1].centre: not a key of a circle (it takes type, center, radius, solid) (did you mean \"center\"?)");
  CHECK(shapes_error("{ { type = \"box\", min = {0, 0}, max = {1, 1} } }") ==
        "t.lua: shapes[1].solid: expected \"inside\" (the box is solid) or \"outside\" (a cage), got a nil");
  CHECK(shapes_error("{ { type = \"box\", min = {0, 0}, max = {1, 1}, solid = \"in\" } }") ==
        "t.lua: shapes[1].solid: expected \"inside\" (the box is solid) or \"outside\" (a cage), got \"in\"");
  // The second entry is named, down to the component.
  const std::string good = "{ type = \"circle\", center = {0, 0}, radius = 0.01, solid = \"inside\" }, ";
  CHECK(shapes_error("{ " + good + "{ type = \"box\", min = 0, max = {1, 1}, solid = \"inside\" } }") ==
        "t.lua: shapes[2].min: expected a point {x, y} of two lengths, got a number");
  CHECK(shapes_error("{ " + good + "{ type = \"box\", min = {0}, max = {1, 1}, solid = \"inside\" } }") ==
        "t.lua: shapes[2].min: expected a point {x, y} of two lengths, got a table of 1 entries");
  CHECK(shapes_error("{ " + good + "{ type = \"box\", min = {0, \"10 N\"}, max = {1, 1}, solid = \"inside\" } }")
            .find("t.lua: shapes[2].min[2]: expected a length (m), got a force") == 0);
  CHECK(shapes_error("{ " + good + "{ type = \"box\", min = {0, \"10 mmm\"}, max = {1, 1}, solid = \"inside\" } }")
            .find("t.lua: shapes[2].min[2]: unknown unit") == 0);
  CHECK(shapes_error("{ " + good + "{ type = \"box\", min = {0, true}, max = {1, 1}, solid = \"inside\" } }") ==
        "t.lua: shapes[2].min[2]: expected a length (a number in m or a string such as \"10 mm\"), got a boolean");
  CHECK(shapes_error("{ { type = \"box\", min = {0, 0}, max = {1, 0/0}, solid = \"inside\" } }")
            .find("t.lua: shapes[1].max[2]: expected a finite length") == 0);
  CHECK(shapes_error("{ { type = \"box\", min = {0, 0}, max = {0, 1}, solid = \"inside\" } }") ==
        "t.lua: shapes[1]: need min < max in x and in y, got min (0, 0) mm, max (0, 1000) mm");
  CHECK(shapes_error("{ { type = \"circle\", center = {0, 0}, radius = \"0 mm\", solid = \"inside\" } }") ==
        "t.lua: shapes[1].radius: expected a radius above 0, got 0 mm");
  CHECK(shapes_error("{ { type = \"circle\", center = {0, 0}, solid = \"inside\" } }")
            .find("t.lua: shapes[1].radius: expected a length") == 0);
}

TEST_CASE("script shapes: a 1-D scene refuses them, after its own dimension check") {
  const std::string one_d = "shapes = { { type = \"circle\", center = {0, 0}, radius = 0.01, solid = \"inside\" } }\n"
                            "function force(s) return -100 * s.x end\n";
  const std::string error = script_load_error(one_d);
  CHECK(error == "t.lua: shapes: this is a 1-D scene, and shapes are for 2-D scripts (validate presses into them in "
                 "a 2-DOF scene; a 1-D scene's walls are found by a scan of the field): remove shapes, or use the "
                 "script in a planar environment");
  // The shipped 2-D box in a 1-D scene still says it is a 2-D script first.
  CHECK_THROWS_WITH_AS(compile_script("scripts/planar/box.lua", read_script("planar/box.lua"),
                                      nlohmann::json::object(), "", "", {}, 1),
                       doctest::Contains("s.y is only in 2-D scenes"), InputError);
  // A bad entry is reported in a 1-D scene too (the table is read at load).
  CHECK(script_load_error("shapes = { 1 }\nfunction force(s) return 0 end\n").find("t.lua: shapes[1]: expected a table") == 0);
}
