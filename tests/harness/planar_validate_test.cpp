// `hapscene validate` on 2-DOF scenes as a library call (engine/harness/planar_validate.hpp):
// every scenario builds and runs deterministically, the hand never drags the handle
// through a solid on its own way, each 2-D check can fail (a penetration-only crossing
// pops through, a scene that lingers near a singular pose, a wall far above the bound
// creates energy), the per-pose stiffness bound, the planar "validate" block and the
// JSON report's fields.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/devices/planar/planar_hand.hpp"
#include "engine/harness/planar_bound.hpp"
#include "engine/harness/planar_report.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/load/environment.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

PlanarEnvironment planar_environment(const std::string& effects, const std::string& extra = "",
                                     const std::string& device = "haplink") {
  return compile_planar_environment(R"({"name": "t", "device": ")" + device + R"(", )" + extra + R"("effects": [)" +
                                        effects + "]}",
                                    "env.json");
}

const char* kBox =
    R"({"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "inside"})";
// A bar 1 mm thick below home, and a circle and a wall away from it.
const char* kShapes =
    R"({"type": "polygon", "points": [["-40 mm", "125 mm"], ["10 mm", "125 mm"], ["10 mm", "126 mm"], ["-40 mm", "126 mm"]], "stiffness": 200, "solid": "inside"},
       {"type": "circle", "center": ["-50 mm", "150 mm"], "radius": "6 mm", "stiffness": 100, "solid": "inside"},
       {"type": "wall", "point": [0, "100 mm"], "normal": [0, 1], "stiffness": 100})";

const CheckResult* find_check(const PlanarScenarioResult& result, const std::string& name) {
  for (const CheckResult& c : result.checks) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

TEST_CASE("planar validate: every scenario builds from the scene and runs, the same every time") {
  const PlanarEnvironment env = planar_environment(kShapes);
  HarnessOptions options;
  options.thresholds = env.validate;
  for (std::size_t i = 0; i < std::size(kPlanarValidateNames); ++i) {
    const auto kind = static_cast<PlanarValidateKind>(i);
    CAPTURE(kPlanarValidateNames[i]);
    CHECK(planar_validate_kind_named(kPlanarValidateNames[i]) == kind);
    const PlanarValidateScenario scenario = build_planar_validate_scenario(kind, env.scene, options);
    REQUIRE(scenario.applicable);
    CHECK(scenario.duration_s > 0.0);
    CHECK(scenario.duration_s < 120.0);
    const PlanarScenarioResult a = run_planar_validate_scenario(env.scene, scenario, options);
    const PlanarScenarioResult b = run_planar_validate_scenario(env.scene, scenario, options);
    REQUIRE(a.records.size() == b.records.size());
    CHECK(a.records.size() == static_cast<std::size_t>(std::llround(scenario.duration_s * 1000.0)));
    for (std::size_t k = 0; k < a.records.size(); k += 97) CHECK(a.records[k].x_true_m == b.records[k].x_true_m);
    CHECK(a.checks.size() == b.checks.size());
    CHECK(find_check(a, "pop_through") != nullptr);
    CHECK(find_check(a, "singularity") != nullptr);
    CHECK(find_check(a, "slip") == nullptr);  // planar profiles give no slip force
  }
  CHECK(!planar_validate_kind_named("line"));
}

TEST_CASE("planar validate: press and swipe need shapes, the swipe finds the thin bar only") {
  const PlanarEnvironment spring = planar_environment(R"({"type": "spring", "stiffness": 50, "center": ["-16 mm", "130 mm"]})");
  HarnessOptions options;
  CHECK(!build_planar_validate_scenario(PlanarValidateKind::press, spring.scene, options).applicable);
  CHECK(!build_planar_validate_scenario(PlanarValidateKind::swipe, spring.scene, options).applicable);
  const PlanarEnvironment box = planar_environment(kBox);
  const PlanarValidateScenario press = build_planar_validate_scenario(PlanarValidateKind::press, box.scene, options);
  CHECK(press.description.find("4 edge and 4 corner places") != std::string::npos);
  CHECK(!build_planar_validate_scenario(PlanarValidateKind::swipe, box.scene, options).applicable);

  const PlanarEnvironment shapes = planar_environment(kShapes);
  const std::vector<PlanarPressPlace> places = planar_press_places(planar_shape_list(shapes.scene), shapes.scene.device.home_m);
  int thin = 0;
  for (const PlanarPressPlace& place : places) thin += place.thickness_m <= kThinWidth_m ? 1 : 0;
  CHECK(thin == 2);  // the bar's two long edges (its ends are 50 mm long across)
  const PlanarValidateScenario swipe = build_planar_validate_scenario(PlanarValidateKind::swipe, shapes.scene, options);
  CHECK(swipe.applicable);
  CHECK(swipe.description.find("2 thin places") != std::string::npos);
}

TEST_CASE("planar validate: the hand's own travel never goes through a solid") {
  const PlanarEnvironment env = planar_environment(kBox);
  HarnessOptions options;
  const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(env.scene);
  for (const PlanarValidateKind kind : {PlanarValidateKind::sweep, PlanarValidateKind::press}) {
    const PlanarValidateScenario s = build_planar_validate_scenario(kind, env.scene, options);
    const PlanarHand hand(s.hand, s.start_m);
    double deepest_m = -1.0;
    for (double t = 0.0; t < s.duration_s; t += 0.002) deepest_m = std::max(deepest_m, shapes[0].depth_m(hand.reference_m(t)));
    CAPTURE(kPlanarValidateNames[static_cast<int>(kind)]);
    if (kind == PlanarValidateKind::sweep) CHECK(deepest_m < 0.0);          // round the box
    if (kind == PlanarValidateKind::press) CHECK(deepest_m == doctest::Approx(0.015).epsilon(0.01));  // only the presses
  }
}

TEST_CASE("planar validate: the shipped lab scenes at their stiffness, and far above it" *
          doctest::test_suite("sweeps")) {
  HarnessOptions options;
  for (const char* name : {"haplink_box_inside", "haplink_box_outside", "haplink_circle_inside", "haplink_circle_outside",
                           "haply2diy_v3_box_inside", "haply2diy_v3_box_outside", "haply2diy_v3_circle_inside",
                           "haply2diy_v3_circle_outside"}) {
    CAPTURE(name);
    const PlanarEnvironment env = load_planar_environment(test::source_path(std::string("environments/planar/") + name + ".json"));
    options.thresholds = env.validate;
    const PlanarValidationReport report = validate_planar_scene(env.scene, {}, options);
    CHECK(report.pass);
    CHECK(report.scenarios.size() == 7);
  }
  // Ten times the shipped stiffness: the Haplink's wall chatters under the presses...
  std::string text = text_of(test::source_path("environments/planar/haplink_box_inside.json"));
  text.replace(text.find("\"200 N/m\""), 9, "\"2000 N/m\"");
  const PlanarEnvironment stiff = compile_planar_environment(text, "stiff.json", test::source_path("environments/planar"));
  options.thresholds = stiff.validate;
  const PlanarValidationReport report = validate_planar_scene(stiff.scene, {PlanarValidateKind::press}, options);
  CHECK(!report.pass);
  const CheckResult* jitter = find_check(report.scenarios[0], "jitter");
  REQUIRE(jitter != nullptr);
  CHECK(!jitter->pass);
  // ... and the 2DIY's box, let go from inside it, creates more energy than its joints'
  // viscous and Coulomb losses take out.
  std::string haply = text_of(test::source_path("environments/planar/haply2diy_v3_box_inside.json"));
  haply.replace(haply.find("\"300 N/m\""), 9, "\"3000 N/m\"");
  const PlanarEnvironment haply_stiff = compile_planar_environment(haply, "stiff.json", test::source_path("environments/planar"));
  options.thresholds = haply_stiff.validate;
  const PlanarValidationReport released = validate_planar_scene(haply_stiff.scene, {PlanarValidateKind::release}, options);
  const CheckResult* passivity = find_check(released.scenarios[0], "passivity");
  REQUIRE(passivity != nullptr);
  CHECK(!passivity->pass);
  CHECK(passivity->value > 1.5);
}

TEST_CASE("planar validate: pop_through counts a crossing the rendering lets through, not one it holds") {
  // A 1 mm bar with its god-object proxy, swiped at 500 mm/s: never through.
  const PlanarEnvironment env = planar_environment(kShapes);
  HarnessOptions options;
  const PlanarValidationReport report = validate_planar_scene(env.scene, {PlanarValidateKind::swipe}, options);
  const CheckResult* pop = find_check(report.scenarios[0], "pop_through");
  REQUIRE(pop != nullptr);
  CHECK(pop->value == 0.0);
  CHECK(pop->pass);

  // The same handle path rendered by depth alone (no proxy: the "proxy" is the handle):
  // straight down across the bar, it pops through once.
  const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(env.scene);
  std::vector<PlanarValidateRecord> records;
  std::vector<Vec2> proxies;
  for (int k = 0; k <= 40; ++k) {
    PlanarValidateRecord r;
    r.t_s = k * 1e-3;
    r.x_true_m = Vec2{{-0.015, 0.1275 - k * 1e-4}};
    records.push_back(r);
    for (std::size_t i = 0; i < shapes.size(); ++i) proxies.push_back(r.x_true_m);
  }
  PlanarScenarioMetrics m;
  count_pop_throughs(shapes, records, proxies, &m);
  // The shapes in the proxies' order: wall, circle, then the bar.
  REQUIRE(shapes[2].kind == PlanarShapeKind::polygon);
  CHECK(m.pop_throughs == 1);
  CHECK(m.first_pop_shape == 2);
  CHECK(m.first_pop_x_m[1] < 0.125 + 1e-9);
  // With the proxy held on the top face, the same path is not a pop-through.
  for (std::size_t k = 0; k < records.size(); ++k) proxies[k * shapes.size() + 2] = Vec2{{-0.015, 0.126}};
  PlanarScenarioMetrics held;
  count_pop_throughs(shapes, records, proxies, &held);
  CHECK(held.pop_throughs == 0);
}

TEST_CASE("planar validate: a scene that lingers near a singular pose fails the singularity check") {
  // The Haplink with a strict condition limit (4.5: the arm stretched toward the top left
  // of its workspace passes it), a spring pulling from there, the handle left there.
  const test::ScratchFolder folder("planar_validate_singular");
  std::string profile = text_of(test::source_path("environments/devices/haplink.json"));
  profile.replace(profile.find("\"condition_limit\": 20"), 21, "\"condition_limit\": 4.5");
  folder.write("strict.json", profile);
  const PlanarEnvironment env =
      compile_planar_environment(R"({"name": "s", "device": "strict.json", "effects": [{"type": "spring", "stiffness": 50, "center": ["-20 mm", "140 mm"]}]})",
                                 "s.json", folder.dir.string());
  HarnessOptions options;
  options.free_start_planar_m = Vec2{{-0.065, 0.162}};
  const PlanarValidationReport report = validate_planar_scene(env.scene, {PlanarValidateKind::free}, options);
  const CheckResult* singular = find_check(report.scenarios[0], "singularity");
  REQUIRE(singular != nullptr);
  CHECK(!singular->pass);
  CHECK(singular->value > 100.0);
  CHECK(singular->detail.find("of limit 4.5") != std::string::npos);
  CHECK(report.scenarios[0].metrics.max_condition > 4.5);
  // The default limit (20) never acts there.
  const PlanarEnvironment relaxed = planar_environment(R"({"type": "spring", "stiffness": 50, "center": ["-20 mm", "140 mm"]})");
  const PlanarValidationReport fine = validate_planar_scene(relaxed.scene, {PlanarValidateKind::free}, options);
  CHECK(find_check(fine.scenarios[0], "singularity")->pass);
}

TEST_CASE("planar validate: the stiffness bound per pose over the workspace") {
  const PlanarEnvironment haplink = planar_environment(kBox);
  const PlanarStiffnessBound b = planar_stiffness_bound(haplink.scene);
  CHECK(b.grid == 11);
  CHECK(b.poses.size() > 100);
  CHECK(b.stiffest_N_per_m == 200.0);
  CHECK(b.lowest.bound_N_per_m < b.highest.bound_N_per_m);
  for (const PlanarPoseBound& pose : b.poses) {
    CHECK(pose.bound_N_per_m == std::min(pose.viscous_N_per_m, pose.coulomb_N_per_m));
    CHECK(pose.bound_N_per_m >= b.lowest.bound_N_per_m);
  }
  // The Haplink's coarse encoders bind: 2fc/D, 42 N/m at the stretched top left corner.
  CHECK(std::string(b.lowest.name) == "2fc/D");
  CHECK(b.lowest.bound_N_per_m == doctest::Approx(42.2).epsilon(0.01));
  CHECK(b.lowest.x_m[0] == doctest::Approx(-0.07));
  // 2b/T scales with the rate, 2fc/D does not.
  const PlanarEnvironment fast = planar_environment(kBox, R"("rate_hz": 2000, )");
  const PlanarStiffnessBound f = planar_stiffness_bound(fast.scene);
  REQUIRE(f.poses.size() == b.poses.size());
  CHECK(f.poses[0].viscous_N_per_m == doctest::Approx(2.0 * b.poses[0].viscous_N_per_m));
  CHECK(f.poses[0].coulomb_N_per_m == doctest::Approx(b.poses[0].coulomb_N_per_m));
}

TEST_CASE("planar validate: the validate block takes the 2-D keys and refuses the 1-D ones, saying why") {
  const PlanarEnvironment env = planar_environment(
      kBox, R"("validate": {"max_force": "1 N", "max_pop_through": 2, "max_singularity_ticks": 5, "max_penetration": "4 mm", "release_from": "12 mm"}, )");
  CHECK(env.validate.max_force_N == 1.0);
  CHECK(env.validate.max_pop_through == 2);
  CHECK(env.validate.max_singularity_ticks == 5);
  CHECK(env.validate.max_penetration_m == doctest::Approx(0.004));
  HarnessOptions options;
  options.thresholds = env.validate;
  const PlanarValidationReport report = validate_planar_scene(env.scene, {PlanarValidateKind::press}, options);
  CHECK(!find_check(report.scenarios[0], "max_force")->pass);
  CHECK(find_check(report.scenarios[0], "max_force")->threshold == 1.0);
  CHECK(find_check(report.scenarios[0], "pop_through")->threshold == 2.0);
  CHECK_THROWS_WITH_AS(planar_environment(kBox, R"("validate": {"max_slip_ticks": 0}, )"),
                       doctest::Contains("env.json: /validate/max_slip_ticks: a 2-DOF scene has no slip check"), InputError);
  CHECK_THROWS_WITH_AS(planar_environment(kBox, R"("validate": {"stiff_threshold": "100 N/m"}, )"),
                       doctest::Contains("/validate/stiff_threshold: a 2-DOF scene's walls are its shapes"), InputError);
  CHECK_THROWS_WITH_AS(planar_environment(kBox, R"("validate": {"max_pop_through": -1}, )"),
                       doctest::Contains("/validate/max_pop_through"), InputError);
  CHECK_THROWS_WITH_AS(planar_environment(kBox, R"("validate": {"max_penetraton": "1 mm"}, )"),
                       doctest::Contains("/validate"), InputError);
  // A 1-DOF block refuses the 2-D keys (unknown there).
  CHECK_THROWS_AS(compile_environment(R"({"effects": [], "validate": {"max_pop_through": 0}})", "one.json"), InputError);
}

TEST_CASE("planar validate: the JSON report keeps the schema and adds the 2-D fields") {
  const PlanarEnvironment env = planar_environment(kBox);
  HarnessOptions options;
  options.free_start_planar_m = Vec2{{-0.01, 0.15}};
  const PlanarValidationReport report =
      validate_planar_scene(env.scene, {PlanarValidateKind::release, PlanarValidateKind::swipe}, options);
  const nlohmann::json j = report_to_json(report);
  CHECK(j["schema"] == "hapscene-validate/2");
  CHECK(j["axes"] == 2);
  CHECK(j["scene"]["axes"] == 2);
  CHECK(j["scene"]["shapes"] == 1);
  CHECK(j["scene"]["stiffness_bound"]["lowest"]["x_m"].size() == 2);
  CHECK(j["scene"]["stiffness_bound"]["lowest"]["bound"] == "2fc/D");
  CHECK(j["scene"]["passivity_bound_N_per_m"] == report.bound.lowest.bound_N_per_m);
  CHECK(j["scene"]["stiffness_bound"]["poses"].size() == report.bound.poses.size());
  CHECK(j["options"]["free_start_m"] == nlohmann::json::array({-0.01, 0.15}));
  const nlohmann::json& release = j["scenarios"][0];
  CHECK(release["name"] == "release");
  CHECK(release["start_m"].size() == 2);
  const nlohmann::json& m = release["metrics"];
  for (const char* key : {"max_output_x_m", "jitter_peak_x_m", "max_penetration_x_m", "max_condition_x_m"}) {
    CAPTURE(key);
    CHECK(m[key].is_array());
    CHECK(m[key].size() == 2);
  }
  CHECK(m["oscillation"]["rest_m"].size() == 2);
  CHECK(m["oscillation"]["major_axis"].size() == 2);
  CHECK(m["first_pop_x_m"].is_null());
  CHECK(m["pop_throughs"] == 0);
  CHECK(m["safety"].contains("pose_hold_ticks"));
  std::vector<std::string> names;
  for (const auto& c : release["checks"]) names.push_back(c["name"]);
  CHECK(names == std::vector<std::string>{"max_force", "time_at_limit", "slew", "passivity", "limit_cycle", "growth",
                                          "penetration", "pop_through", "singularity", "jitter", "script",
                                          "tick_compute"});
  for (std::size_t i = 0; i < names.size(); ++i) CHECK(names[i] == kPlanarCheckNames[i]);
  CHECK(release["checks"][7]["unit"] == "crossings");
  CHECK(j["scenarios"][1]["applicable"] == false);
  CHECK(j["scenarios"][1]["metrics"].is_null());  // the same keys as any scenario, no metrics
  CHECK(j["scenarios"][1]["checks"] == nlohmann::json::array());
}
