// Planar (2-DOF) scenes through the generic tick (SceneOf<2>, step<2>, run_scene<2>): the
// loader picks the scene's axes from its device profile, the tick renders the 2-D effects
// through the linkage, safety acts on the force vector, an untrusted pose holds the force,
// and simulated runs are deterministic.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/runner.hpp"
#include "engine/scene/step.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {

PlanarScene planar(const std::string& effects, const std::string& extra = "", const std::string& device = "haplink") {
  return load_planar_environment_text(
      R"({"name": "t", "device": ")" + device + R"(", )" + extra + R"("effects": [)" + effects + "]}", "env.json");
}

// Records every tick's handle position and commanded force.
class Trace final : public TickObserverOf<2> {
 public:
  void on_tick(const TickStateOf<2>& s) noexcept override {
    if (x_m.size() < x_m.capacity()) {
      x_m.push_back(s.x_m);
      output_N.push_back(s.output_N);
    }
  }
  std::vector<Vec2> x_m;
  std::vector<Vec2> output_N;
};

struct PlanarRun {
  RunSummaryOf<2> summary;
  std::vector<Vec2> x_m;
  std::vector<Vec2> output_N;
};

PlanarRun run(const PlanarScene& scene, const PlanarHandConfig& hand, const Vec2& start_m, double duration_s) {
  PlanarSimulationConfig config;
  config.hand = hand;
  config.start_q_rad = planar_joint_angles_at(scene.device, start_m);
  SimulatedPlanar device(scene.device, config);
  Trace trace;
  trace.x_m.reserve(static_cast<std::size_t>(duration_s * scene.rate_hz) + 1);
  trace.output_N.reserve(trace.x_m.capacity());
  RunOptions options;
  options.duration_s = duration_s;
  options.pacing = Pacing::simulated_time;
  PlanarRun result{run_scene(scene, device, options, &trace), {}, {}};
  result.x_m = std::move(trace.x_m);
  result.output_N = std::move(trace.output_N);
  return result;
}

}  // namespace

TEST_CASE("planar scene: the loader picks two axes from a planar profile, one from a capstan profile") {
  CHECK(environment_axes(test::source_path("environments/planar/haplink_box_inside.json")) == 2);
  CHECK(environment_axes(test::source_path("environments/planar/haply2diy_v3_circle_outside.json")) == 2);
  CHECK(environment_axes(test::source_path("environments/spring.json")) == 1);
  CHECK(environment_axes(test::source_path("scripts/bumps.lua")) == 1);
  const PlanarScene scene = planar(R"({"type": "spring", "stiffness": "100 N/m", "center": ["-16 mm", "130 mm"]})");
  CHECK(scene.device.name == "haplink");
  CHECK(scene.bank.group<PlanarSpring>().size() == 1);
  CHECK(scene.safety.max_force_N == 2.0);
  CHECK(scene.safety.workspace_min_m == Vec2{{-0.07, 0.09}});
}

TEST_CASE("planar scene: a 1-D form, a 1-D profile or harness thresholds are load errors that say so") {
  CHECK_THROWS_WITH_AS(planar(R"({"type": "spring", "stiffness": 100, "center": 0.01})"),
                       doctest::Contains("/effects/0/center"), InputError);
  CHECK_THROWS_WITH_AS(planar(R"({"type": "spring", "stiffness": 100})", R"("validate": {"stiff_threshold": 1}, )"),
                       doctest::Contains("/validate/stiff_threshold: a 2-DOF scene's walls are its shapes"), InputError);
  CHECK_THROWS_WITH_AS(planar(R"({"type": "damper", "damping": 1})", "", "hapkit3"),
                       doctest::Contains("env.json: /device:"), InputError);
  CHECK_THROWS_WITH_AS(load_environment_text(R"({"device": "haplink", "effects": []})", "env.json"),
                       doctest::Contains("a 2-DOF (planar) profile"), InputError);
  CHECK_THROWS_WITH_AS(planar(R"({"type": "damper", "damping": 1})", R"("safety": {"max_force": "5 N"}, )"),
                       doctest::Contains("must not exceed the device's 2 N"), InputError);
}

TEST_CASE("planar scene: the tick renders a spring through the linkage, J^T F to the motors") {
  const PlanarScene scene = planar(R"({"type": "spring", "stiffness": "100 N/m", "center": ["-10 mm", "140 mm"]})");
  TickStateOf<2> state = make_tick_state(scene);
  const PlanarModel& model = scene.device_model.model;
  // The handle held at the arm's zero pose: (-16.33, 142.34) mm.
  const PlanarReading reading = planar_reading_for(model, Vec2{});
  for (int i = 0; i < 1000; ++i) step(scene, reading, &state);  // past the soft start
  const Vec2 expected_N = Vec2{{-0.01, 0.14}} - state.x_m;
  CHECK(state.x_m[0] == doctest::Approx(-0.016327652).epsilon(1e-3));
  CHECK(state.output_N[0] == doctest::Approx(100.0 * expected_N[0]));
  CHECK(state.output_N[1] == doctest::Approx(100.0 * expected_N[1]));
  // The command is what the model makes of that force at this pose.
  const PlanarMotorCommand command = planar_motor_command(model, state.sensor.pose.jacobian, state.output_N);
  CHECK(state.command.motor[0].duty == command.motor[0].duty);
  CHECK(state.command.motor[1].duty == command.motor[1].duty);
  CHECK(state.command.motor[0].duty > 0.0);
}

TEST_CASE("planar safety: the force limit keeps the direction, outside the workspace nothing is rendered") {
  const PlanarScene scene = planar(R"({"type": "spring", "stiffness": "1000 N/m", "center": ["30 mm", "160 mm"]})");
  SafetyCounters counters;
  const Vec2 x{{-0.02, 0.12}};
  const Vec2 asked = Vec2{{1000.0 * 0.05, 1000.0 * 0.04}};
  const Vec2 out = apply_static_safety(scene.safety, x, asked, &counters);
  CHECK(norm(out) == doctest::Approx(2.0));
  CHECK(out[0] / out[1] == doctest::Approx(asked[0] / asked[1]));
  CHECK(counters.clamped_ticks == 1);
  CHECK(apply_static_safety(scene.safety, Vec2{{0.05, 0.12}}, Vec2{{0.1, 0.0}}, &counters) == Vec2{});
  CHECK(counters.outside_workspace_ticks == 1);
  const double nan = std::nan("");
  CHECK(apply_static_safety(scene.safety, x, Vec2{{nan, 0.0}}, &counters) == Vec2{});
  CHECK(counters.nonfinite_faults == 1);
}

TEST_CASE("planar safety: a polygon workspace renders nothing outside the polygon, inside its box") {
  // The Haplink's profile with a triangle for a workspace.
  test::ScratchFolder scratch("planar_polygon_workspace");
  std::ifstream file(test::source_path("environments/devices/haplink.json"));
  std::string profile((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::string box = R"("workspace": {"box": {"min": ["-70 mm", "90 mm"], "max": ["40 mm", "165 mm"]}})";
  REQUIRE(profile.find(box) != std::string::npos);
  profile.replace(profile.find(box), box.size(),
                  R"("workspace": {"polygon": [["-70 mm", "90 mm"], ["40 mm", "165 mm"], ["-70 mm", "165 mm"]]})");
  scratch.write("triangle.json", profile);
  const PlanarScene scene = load_planar_environment_text(
      R"({"device": "triangle.json", "effects": [{"type": "damper", "damping": 1}]})", "env.json", scratch.dir.string());
  REQUIRE(scene.safety.workspace_polygon_m.size() == 3);
  SafetyCounters counters;
  // Inside the triangle: passed; inside its bounding box but past the hypotenuse: nothing.
  CHECK(apply_static_safety(scene.safety, Vec2{{-0.06, 0.15}}, Vec2{{0.5, 0.5}}, &counters) == Vec2{{0.5, 0.5}});
  CHECK(apply_static_safety(scene.safety, Vec2{{0.03, 0.1}}, Vec2{{0.5, 0.5}}, &counters) == Vec2{});
  CHECK(counters.outside_workspace_ticks == 1);
}

TEST_CASE("planar safety: an environment's box narrows a polygon workspace, never replaces it") {
  // The Haplink's profile with a notched workspace: the notch x in [10, 30] mm, y above 120 mm.
  test::ScratchFolder scratch("planar_notched_workspace");
  std::ifstream file(test::source_path("environments/devices/haplink.json"));
  std::string profile((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::string box = R"("workspace": {"box": {"min": ["-70 mm", "90 mm"], "max": ["40 mm", "165 mm"]}})";
  REQUIRE(profile.find(box) != std::string::npos);
  profile.replace(profile.find(box), box.size(),
                  R"("workspace": {"polygon": [["-70 mm", "90 mm"], ["40 mm", "90 mm"], ["40 mm", "165 mm"],
                     ["30 mm", "165 mm"], ["30 mm", "120 mm"], ["10 mm", "120 mm"], ["10 mm", "165 mm"],
                     ["-70 mm", "165 mm"]]})");
  scratch.write("notched.json", profile);
  const auto load = [&](const std::string& min, const std::string& max) {
    return load_planar_environment_text(R"({"device": "notched.json", "safety": {"workspace": {"min": )" + min +
                                            R"(, "max": )" + max + R"(}}, "effects": [{"type": "damper", "damping": 1}]})",
                                        "env.json", scratch.dir.string());
  };
  // Its four corners inside the polygon, but across the notch: refused, naming the edge.
  CHECK_THROWS_WITH_AS(load(R"(["0 mm", "100 mm"])", R"(["35 mm", "160 mm"])"),
                       "env.json: /safety/workspace: must lie within the device's workspace: edge 3 (points 3 to 4) "
                       "of the device's polygon passes through the box",
                       InputError);
  CHECK_THROWS_WITH_AS(load(R"(["0 mm", "100 mm"])", R"(["50 mm", "160 mm"])"),
                       "env.json: /safety/workspace: must lie within the device's workspace: its corner (0.05, 0.1) m "
                       "is outside it",
                       InputError);
  // Within it: the box narrows, and the polygon is still tested.
  const PlanarScene scene = load(R"(["-60 mm", "100 mm"])", R"(["5 mm", "160 mm"])");
  CHECK(scene.safety.workspace_min_m == Vec2{{-0.06, 0.1}});
  CHECK(scene.safety.workspace_max_m == Vec2{{0.005, 0.16}});
  CHECK(scene.safety.workspace_polygon_m.size() == 8);
  CHECK(within_workspace(scene.safety, Vec2{{-0.03, 0.13}}));
  CHECK_FALSE(within_workspace(scene.safety, Vec2{{0.02, 0.14}}));  // the notch, outside the box as well
}

TEST_CASE("planar tick: a pose near a singularity ramps the force out and counts it") {
  const PlanarScene scene = planar(R"({"type": "spring", "stiffness": "100 N/m", "center": ["-10 mm", "140 mm"]})");
  TickStateOf<2> state = make_tick_state(scene);
  const PlanarModel& model = scene.device_model.model;
  const PlanarReading home = planar_reading_for(model, Vec2{});
  for (int i = 0; i < 1000; ++i) step(scene, home, &state);
  REQUIRE(norm(state.output_N) > 0.1);
  // The arm stretched straight (link b in line with link a) is singular.
  const Vec2 straight{{0.0, -model.linkage.serial.offset_b_rad}};
  const PlanarReading stretched = planar_reading_for(model, straight);
  double previous_N = norm(state.output_N);
  for (int i = 0; i < 50; ++i) {
    step(scene, stretched, &state);
    CHECK(norm(state.output_N) <= previous_N + 1e-12);
    previous_N = norm(state.output_N);
  }
  CHECK(state.safety.counters.pose_hold_ticks == 50);
  CHECK(previous_N < 1e-9);
}

TEST_CASE("planar run: the box cage holds the hand in, and two runs are identical to the bit") {
  const PlanarScene scene = load_planar_environment_file(test::source_path("environments/planar/haplink_box_outside.json"));
  const PlanarBox& cage = scene.bank.group<PlanarBox>().at(0);
  PlanarHandConfig hand;
  hand.motion = PlanarHandMotion::line;
  hand.line_from_m = Vec2{{-0.016, 0.13}};
  hand.line_to_m = Vec2{{-0.016, 0.162}};  // 7 mm past the cage's top wall (at 155 mm)
  hand.speed_m_per_s = 0.05;
  hand.stiffness_N_per_m = 100.0;
  const PlanarRun first = run(scene, hand, Vec2{{-0.016, 0.13}}, 2.0);
  const PlanarRun second = run(scene, hand, Vec2{{-0.016, 0.13}}, 2.0);
  CHECK(first.x_m == second.x_m);
  CHECK(first.output_N == second.output_N);
  // The wall pushes down (-y) and the handle stays within a few mm of it while the hand
  // pulls 7 mm beyond (at rest: 100 N/m against 200 N/m, 2.3 mm in).
  double deepest_m = 0.0;
  double strongest_down_N = 0.0;
  for (std::size_t i = 0; i < first.x_m.size(); ++i) {
    deepest_m = std::max(deepest_m, first.x_m[i][1] - cage.max_m[1]);
    strongest_down_N = std::min(strongest_down_N, first.output_N[i][1]);
  }
  CHECK(strongest_down_N < -0.3);
  CHECK(deepest_m > 0.001);
  CHECK(deepest_m < 0.004);
  CHECK(first.summary.safety.nonfinite_faults == 0);
}

}  // namespace HAPSCENE_TEST_FILE
