// Shapes a 2-D script declares (`shapes`) drive validate's scenarios as the built-in
// shapes do: the scripted twins of the lab's box and circle get the same scenarios (the
// same hand paths) as their built-in twins, the shape list keeps the built-ins first (so
// their proxies stay where the run records them), and a declared shape's pop-through is
// judged by the direction of the force: a thin scripted box (open loop, no proxy) lets
// the handle through where the built-in holds it.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "engine/harness/planar_metrics.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/harness/planar_validate_scenario.hpp"
#include "engine/load/environment.hpp"
#include "tests/harness/planar_harness_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;

TEST_CASE("script shapes in validate: the scripted twins get their built-in twins' scenarios") {
  const HarnessOptions options;
  for (const char* name : {"box_inside", "box_outside", "circle_inside", "circle_outside"}) {
    CAPTURE(name);
    const PlanarScene builtin = test::shipped_planar(std::string("haplink_") + name);
    const PlanarScene scripted = test::shipped_planar(std::string("haplink_script_") + name);
    REQUIRE(planar_scenario_shapes(scripted).size() == 1);
    CHECK(planar_scenario_shapes(scripted)[0].declared);
    CHECK(planar_shape_list(scripted).empty());  // no proxy: figures and traces see none
    for (std::size_t k = 0; k < std::size(kPlanarValidateNames); ++k) {
      const auto kind = static_cast<PlanarValidateKind>(k);
      CAPTURE(kPlanarValidateNames[k]);
      const PlanarValidateScenario a = build_planar_validate_scenario(kind, builtin, options);
      const PlanarValidateScenario b = build_planar_validate_scenario(kind, scripted, options);
      CHECK(a.applicable == b.applicable);
      CHECK(a.description == b.description);
      CHECK(a.duration_s == b.duration_s);
      REQUIRE(a.hand.path.size() == b.hand.path.size());
      for (std::size_t i = 0; i < a.hand.path.size(); ++i) {
        CHECK(a.hand.path[i].t_s == b.hand.path[i].t_s);
        CHECK(a.hand.path[i].p_m[0] == b.hand.path[i].p_m[0]);
        CHECK(a.hand.path[i].p_m[1] == b.hand.path[i].p_m[1]);
        CHECK(a.hand.path[i].grip == b.hand.path[i].grip);
      }
    }
  }
  // The press of the scripted box: the built-in's places, and it passes.
  const PlanarValidationReport report =
      validate_planar_scene(test::shipped_planar("haplink_script_box_inside"), {PlanarValidateKind::press}, options);
  CHECK(report.shapes == 1);
  REQUIRE(report.scenarios.size() == 1);
  CHECK(report.scenarios[0].scenario.description.find("4 edge and 4 corner places of 1 shapes") != std::string::npos);
  CHECK(report.pass);
  REQUIRE(test::check_named(report.scenarios[0], "pop_through") != nullptr);
  CHECK(test::check_named(report.scenarios[0], "penetration")->value > 0.001);
}

TEST_CASE("script shapes in validate: built-in scenes keep their shape list") {
  for (const char* name : {"haplink_box_inside", "haplink_circle_outside", "haply2diy_v3_box_outside"}) {
    CAPTURE(name);
    const PlanarScene scene = test::shipped_planar(name);
    const std::vector<PlanarShapeGeometry> all = planar_scenario_shapes(scene);
    const std::vector<PlanarShapeGeometry> built_in = planar_shape_list(scene);
    REQUIRE(all.size() == built_in.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
      CHECK(all[i].kind == built_in[i].kind);
      CHECK_FALSE(all[i].declared);
      CHECK(all[i].outline == built_in[i].outline);
    }
  }
  // A built-in shape and a script's declared one: the built-in first.
  const PlanarScene mixed = compile_planar_environment(
                                std::string(R"({"name": "t", "device": "haplink", "effects": [)") +
                                    R"({"type": "script", "file": ")" + HAPSCENE_SOURCE_DIR +
                                    R"(/scripts/planar/circle.lua"},)" +
                                    R"({"type": "box", "min": ["-40 mm", "90 mm"], "max": ["0 mm", "100 mm"], "stiffness": 200, "solid": "inside"}]})",
                                "env.json")
                                .scene;
  const std::vector<PlanarShapeGeometry> shapes = planar_scenario_shapes(mixed);
  REQUIRE(shapes.size() == 2);
  CHECK(shapes[0].kind == PlanarShapeKind::box);
  CHECK_FALSE(shapes[0].declared);
  CHECK(shapes[1].kind == PlanarShapeKind::circle);
  CHECK(shapes[1].declared);
  // The run records a point per scenario shape each tick (the handle for the declared one).
  const PlanarValidationReport report = validate_planar_scene(mixed, {PlanarValidateKind::hold}, HarnessOptions{});
  REQUIRE(report.scenarios.size() == 1);
  const PlanarScenarioResult& hold = report.scenarios[0];
  REQUIRE(hold.proxies_m.size() == 2 * hold.records.size());
  CHECK(hold.proxies_m[3][0] == hold.records[1].x_m[0]);
  CHECK(hold.proxies_m[3][1] == hold.records[1].x_m[1]);
}

TEST_CASE("script shapes in validate: a declared shape's pop-through follows the force") {
  PlanarShapeGeometry box;
  box.kind = PlanarShapeKind::box;
  box.declared = true;
  box.points_m = {Vec2{{0.0, 0.0}}, Vec2{{0.01, 0.0}}, Vec2{{0.01, 0.004}}, Vec2{{0.0, 0.004}}};
  auto outline = std::make_shared<const PolygonOutline>(box.points_m, true);
  box.outline = outline.get();
  const std::vector<PlanarShapeGeometry> shapes = {box};
  // The handle crosses the 4 mm bar upward, at x = 5 mm.
  const auto crossing = [](double force_below_N, double force_above_N) {
    std::vector<PlanarValidateRecord> records;
    for (int k = 0; k <= 10; ++k) {
      PlanarValidateRecord r;
      r.t_s = k * 0.001;
      r.x_true_m = Vec2{{0.005, -0.001 + k * 0.0006}};
      const bool in = r.x_true_m[1] > 0.0 && r.x_true_m[1] < 0.004;
      r.requested_N = in ? Vec2{{0.0, r.x_true_m[1] < 0.002 ? force_below_N : force_above_N}} : Vec2{};
      records.push_back(r);
    }
    return records;
  };
  const auto pops = [&](const std::vector<PlanarValidateRecord>& records) {
    PlanarScenarioMetrics m;
    std::vector<Vec2> proxies;
    for (const PlanarValidateRecord& r : records) proxies.push_back(r.x_true_m);
    count_pop_throughs(shapes, records, proxies, &m);
    return m.pop_throughs;
  };
  CHECK(pops(crossing(-1.0, 1.0)) == 1);   // open loop: pushed back, then out through the far side
  CHECK(pops(crossing(-1.0, -1.0)) == 0);  // a proxy's pull back toward the side it came in by
  CHECK(pops(crossing(0.0, 0.0)) == 0);    // no force: the hand alone took it through
  CHECK(pops(crossing(1.0, 1.0)) == 0);    // pulled through from beyond all along (as no proxy pulls back)
}

TEST_CASE("script shapes in validate: a thin scripted box lets the swipe through, its built-in twin holds") {
  const std::string box_min = R"(["-40 mm", "120 mm"])";
  const std::string box_max = R"(["0 mm", "124 mm"])";
  const PlanarScene scripted = compile_planar_environment(
                                   std::string(R"({"name": "t", "device": "haplink", "effects": [)") +
                                       R"({"type": "script", "file": ")" + HAPSCENE_SOURCE_DIR +
                                       R"(/scripts/planar/box.lua", "params": {"min_y": "120 mm", "max_y": "124 mm"}}]})",
                                   "env.json")
                                   .scene;
  const PlanarScene builtin = compile_planar_environment(
                                  R"({"name": "t", "device": "haplink", "effects": [{"type": "box", "min": )" + box_min +
                                      R"(, "max": )" + box_max + R"(, "stiffness": "200 N/m", "solid": "inside"}]})",
                                  "env.json")
                                  .scene;
  const PlanarValidationReport a = validate_planar_scene(builtin, {PlanarValidateKind::swipe}, HarnessOptions{});
  const PlanarValidationReport b = validate_planar_scene(scripted, {PlanarValidateKind::swipe}, HarnessOptions{});
  REQUIRE(a.scenarios.size() == 1);
  REQUIRE(b.scenarios.size() == 1);
  CHECK(a.scenarios[0].scenario.description == b.scenarios[0].scenario.description);
  CHECK(a.scenarios[0].scenario.description.find("across 2 thin places") != std::string::npos);
  CHECK(test::check_named(a.scenarios[0], "pop_through")->pass);
  CHECK(a.pass);
  CHECK_FALSE(test::check_named(b.scenarios[0], "pop_through")->pass);
  CHECK(b.scenarios[0].metrics.pop_throughs > 0);
  CHECK_FALSE(b.pass);
}
