// The bench's 2-D rows: the hand-written 2-D code computes what the engine computes (its
// forces and motor commands equal the built-in scene's open loop over a grid of readings),
// the recorded readings make the scenes act, and the command prints the 2-D table and its
// goals after the 1-D ones (no timing is checked).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "engine/bench/planar_baseline.hpp"
#include "engine/bench/planar_tick_bench.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/step.hpp"
#include "tests/cli/cli_support.hpp"

namespace hapscene {
namespace {

using Tick = void (*)(const PlanarBaselineConstants&, const PlanarReading&, PlanarBaselineState*);

// The engine's open loop at `reading` (sensor stage, the effects without history, the
// command at that pose) against the baseline's tick; returns whether the box pushed.
bool check_against_engine(const PlanarScene& scene, const PlanarBaselineConstants& c, Tick tick,
                          const PlanarReading& reading) {
  const PlanarModel& model = scene.device_model.model;
  PlanarSensorState sensor = make_planar_sensor_state(model);
  const LinkagePose pose = sense_planar(model, reading, &sensor);
  PlanarBaselineState s;
  tick(c, reading, &s);
  REQUIRE(pose.valid == s.valid);
  if (!pose.valid) return false;
  EffectInputOf<2> input;
  input.x_m = pose.handle_m;
  input.dt_s = scene.period_s;
  ScriptList no_scripts;
  const Vec2 force_N = sum_effects_N(scene, input, no_scripts);
  const PlanarMotorCommand command = planar_motor_command(model, pose.jacobian, force_N);
  for (int i = 0; i < 2; ++i) {
    const auto k = static_cast<std::size_t>(i);
    CHECK(std::fabs(s.x_m[i] - pose.handle_m[i]) <= 1e-12);
    CHECK(std::fabs(s.force_N[i] - force_N[i]) <= 1e-9);
    if (!command.saturated) {
      CHECK(std::fabs(s.torque_N_m[i] - command.torque_N_m[i]) <= 1e-12);
      CHECK(std::fabs(s.duty[i] - command.motor[k].duty) <= 1e-9);
      if (std::fabs(command.torque_N_m[i]) > 1e-12) CHECK(s.direction_high[i] == command.motor[k].direction_high);
    }
  }
  return force_N[0] != 0.0 || force_N[1] != 0.0;
}

TEST_CASE("planar bench: the hand-written Haplink box gives the engine's forces and commands over a grid") {
  const PlanarScene scene = load_planar_environment_file("environments/planar/haplink_box_inside.json");
  PlanarBaselineKind kind{};
  PlanarBaselineConstants c;
  REQUIRE(planar_baseline_for(scene, &kind, &c));
  REQUIRE(kind == PlanarBaselineKind::haplink_box);
  // Encoder counts around the pose at the box's middle: about 2 mm a count at the handle.
  const Vec2 q = planar_joint_angles_at(scene.device, Vec2{{-0.020, 0.1225}});
  const PlanarReading middle = planar_reading_for(scene.device_model.model, q);
  int pushed = 0, points = 0;
  for (int i = -20; i <= 20; ++i) {
    for (int j = -20; j <= 20; ++j) {
      PlanarReading reading = middle;
      reading.counts[0] += i;
      reading.counts[1] += j;
      pushed += check_against_engine(scene, c, haplink_box_tick, reading) ? 1 : 0;
      ++points;
    }
  }
  MESSAGE("haplink: ", pushed, " of ", points, " readings inside the box");
  CHECK(pushed > 20);
  CHECK(pushed < points);
}

TEST_CASE("planar bench: the hand-written 2DIY v3 box gives the engine's forces and commands over a grid") {
  const PlanarScene scene = load_planar_environment_file("environments/planar/haply2diy_v3_box_inside.json");
  PlanarBaselineKind kind{};
  PlanarBaselineConstants c;
  REQUIRE(planar_baseline_for(scene, &kind, &c));
  REQUIRE(kind == PlanarBaselineKind::five_bar_box);
  const Vec2 q = planar_joint_angles_at(scene.device, Vec2{{0.019, 0.070}});
  const PlanarReading middle = planar_reading_for(scene.device_model.model, q);
  int pushed = 0, points = 0;
  for (int i = -20; i <= 20; ++i) {
    for (int j = -20; j <= 20; ++j) {
      PlanarReading reading = middle;
      reading.angle_deg[0] += 0.75 * i;
      reading.angle_deg[1] += 0.75 * j;
      pushed += check_against_engine(scene, c, five_bar_box_tick, reading) ? 1 : 0;
      ++points;
    }
  }
  MESSAGE("2DIY v3: ", pushed, " of ", points, " readings inside the box");
  CHECK(pushed > 20);
  CHECK(pushed < points);
}

TEST_CASE("planar bench: the baseline is only for one inside box on the devices it is written for") {
  PlanarBaselineKind kind{};
  PlanarBaselineConstants c;
  CHECK_FALSE(planar_baseline_for(load_planar_environment_file("environments/planar/haplink_circle_outside.json"), &kind, &c));
  CHECK_FALSE(planar_baseline_for(load_planar_environment_file("environments/planar/haplink_box_outside.json"), &kind, &c));
  CHECK_FALSE(planar_baseline_for(load_planar_environment_text(
      R"({"device": "haplink", "effects": [{"type": "box", "min": [-0.04, 0.11], "max": [0, 0.135], "stiffness": 200,
          "solid": "inside"}, {"type": "damper", "damping": 1}]})", "two effects"), &kind, &c));
}

TEST_CASE("planar bench: the recorded sweep makes the scenes push (the 1000-gon and the boxes)") {
  const PlanarScene empty = load_planar_environment_text(R"({"device": "haplink", "effects": []})", "empty");
  const PlanarScene polygon = load_planar_environment_text(regular_polygon_environment(empty, "haplink", 1000), "polygon");
  CHECK(polygon.name == "polygon_1000");
  const PlanarScene haplink_box = load_planar_environment_file("environments/planar/haplink_box_inside.json");
  const PlanarScene haply_box = load_planar_environment_file("environments/planar/haply2diy_v3_box_inside.json");
  for (const PlanarScene* scene : {&polygon, &haplink_box, &haply_box}) {
    const std::vector<PlanarReading> readings = record_planar_readings(*scene, 10.0);
    REQUIRE(readings.size() == 10000u);
    TickStateOf<2> state = make_tick_state(*scene);
    int pushing = 0;
    for (const PlanarReading& reading : readings) {
      step(*scene, reading, &state);
      if (norm(state.effects_force_N) > 0.1) ++pushing;
    }
    MESSAGE(scene->name, ": ", pushing, " of 10000 ticks push more than 0.1 N");
    CHECK(pushing > 100);
  }
  const std::vector<std::int32_t> indices = reading_indices(3);
  CHECK(indices == std::vector<std::int32_t>{0, 1, 2});
}

TEST_CASE("planar bench: the command prints the 2-D table and goals after the 1-D ones") {
  const test::CliOutcome outcome = test::run_cli("bench --seconds 0.3 --passes 1");
  CHECK(outcome.exit_code == 0);
  const std::string& out = outcome.out;
  const std::size_t parts = out.find("what each part of a scene costs");
  const std::size_t table = out.find("2-DOF (planar): the same measure");
  REQUIRE(parts != std::string::npos);
  REQUIRE(table != std::string::npos);
  CHECK(parts < table);
  CHECK(out.find("spring     hand-folded floor") < parts);
  CHECK(out.find("haplink_box_inside       hand-written C++") > table);
  CHECK(out.find("haplink_box_inside       built-in (JSON)") > table);
  CHECK(out.find("haply2diy_v3_box_inside  hand-written C++") > table);
  CHECK(out.find("haplink_circle_outside   built-in (JSON)") != std::string::npos);
  CHECK(out.find("polygon_1000             built-in (JSON)") != std::string::npos);
  CHECK(out.find("2-DOF goals") != std::string::npos);
  CHECK(out.find("haplink_box_inside: built-in ") != std::string::npos);
  CHECK(out.find("haply2diy_v3_box_inside: built-in ") != std::string::npos);
  CHECK(out.find("polygon_1000: built-in median ") != std::string::npos);
  // The Lua spring in 1-D and in 2-D, side by side in the 2-D table, and its goal.
  const std::size_t lua_1d = out.find("spring (1-D)             Lua script");
  const std::size_t lua_2d = out.find("spring_lua_2d            Lua script");
  REQUIRE(lua_1d != std::string::npos);
  REQUIRE(lua_2d != std::string::npos);
  CHECK(table < lua_1d);
  CHECK(lua_1d < lua_2d);
  // The force calls alone (translated, then in the VM alone), and the goal on the calls.
  const std::size_t call_1d = out.find("spring (1-D)             force call ");
  const std::size_t call_2d = out.find("spring_lua_2d            force call ");
  const std::size_t vm_call_2d = out.find("spring_lua_2d            force call, VM only");
  CHECK(lua_2d < call_1d);
  CHECK(call_1d < call_2d);
  CHECK(call_2d < vm_call_2d);
  CHECK(vm_call_2d != std::string::npos);
  CHECK(out.find("spring_lua_2d: its force call ") != std::string::npos);
  CHECK(out.find("the 1-D Lua spring's per returned value (goal <= 1.0x): ") != std::string::npos);
  CHECK(out.find("not measured") == std::string::npos);

  // Planar files given: only they are benched, in the 2-D table.
  const test::CliOutcome one =
      test::run_cli("bench --seconds 0.3 --passes 1 environments/planar/haply2diy_v3_box_inside.json");
  CHECK(one.exit_code == 0);
  CHECK(one.out.find("haply2diy_v3_box_inside  built-in (JSON)") != std::string::npos);
  CHECK(one.out.find("polygon_1000") == std::string::npos);
}

TEST_CASE("planar bench: --callgrind runs the 2-D baseline and the built-in scene, Lua but for a spring, and no baseline, are refused") {
  const test::CliOutcome baseline = test::run_cli(
      "bench --callgrind environments/planar/haplink_box_inside.json --impl baseline --ticks 2000");
  CHECK(baseline.exit_code == 0);
  CHECK(baseline.out.find("callgrind mode: haplink_box_inside, baseline, 2000 ticks") != std::string::npos);
  const test::CliOutcome builtin = test::run_cli(
      "bench --callgrind environments/planar/haply2diy_v3_box_inside.json --impl builtin --ticks 2000");
  CHECK(builtin.exit_code == 0);
  CHECK(builtin.out.find("callgrind mode: haply2diy_v3_box_inside, builtin, 2000 ticks") != std::string::npos);
  const test::CliOutcome lua = test::run_cli("bench --callgrind environments/planar/haplink_box_inside.json --impl lua");
  CHECK(lua.exit_code == 2);
  CHECK(lua.err.find("--impl lua: a 2-DOF environment needs to be one spring") != std::string::npos);
  const test::CliOutcome none = test::run_cli(
      "bench --callgrind environments/planar/haplink_circle_outside.json --impl baseline --ticks 10");
  CHECK(none.exit_code == 2);
}


TEST_CASE("planar bench: the Lua 2-D spring is the built-in 2-D spring's twin, to the bit") {
  const PlanarScene spring = load_planar_environment_text(
      R"({"name": "s", "device": "haplink", "effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["-15 mm", "127.5 mm"]}]})",
      "spring");
  const std::optional<PlanarScene> lua = planar_lua_equivalent(spring);
  REQUIRE(lua);
  CHECK(lua->script_count == 1);
  CHECK(lua->needs.velocity == false);
  CHECK(lua->safety.max_force_N == spring.safety.max_force_N);
  CHECK(lua->period_s == spring.period_s);
  ScriptList scripts = make_script_instances(*lua);
  ScriptList none;
  for (double x = -0.07; x <= 0.04; x += 0.0037) {
    for (double y = 0.09; y <= 0.165; y += 0.0041) {
      EffectInputOf<2> input;
      input.x_m = Vec2{{x, y}};
      input.dt_s = spring.period_s;
      const Vec2 built_in = sum_effects_N(spring, input, none);
      const Vec2 scripted = sum_effects_N(*lua, input, scripts);
      CHECK(scripted[0] == built_in[0]);
      CHECK(scripted[1] == built_in[1]);
    }
  }
  // Nothing else has a Lua twin here.
  CHECK_FALSE(planar_lua_equivalent(load_planar_environment_file("environments/planar/haplink_box_inside.json")));
}

}  // namespace
}  // namespace hapscene
