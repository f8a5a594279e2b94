// The planar tick compiled per device family (PlanarFamily: the sensor, linkage and drive
// branches decided at compile time) computes, tick by tick and to the bit, what the
// general tick computes for the same scene; compile_planar_model names the family of each
// shipped planar profile.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "engine/bench/planar_tick_bench.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec2& a, const Vec2& b) { return same_bits(a[0], b[0]) && same_bits(a[1], b[1]); }

// Every field a tick writes, compared bit for bit.
void check_same_tick(const TickStateOf<2>& a, const TickStateOf<2>& b) {
  CHECK(same_bits(a.x_m, b.x_m));
  CHECK(same_bits(a.effects_force_N, b.effects_force_N));
  CHECK(same_bits(a.output_N, b.output_N));
  CHECK(a.sensor.pose.valid == b.sensor.pose.valid);
  CHECK(same_bits(a.sensor.pose.elbow_1_m, b.sensor.pose.elbow_1_m));
  CHECK(same_bits(a.sensor.pose.elbow_2_m, b.sensor.pose.elbow_2_m));
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 2; ++c) CHECK(same_bits(a.sensor.pose.jacobian.m[r][c], b.sensor.pose.jacobian.m[r][c]));
  }
  CHECK(same_bits(a.sensor.joints.q_rad, b.sensor.joints.q_rad));
  CHECK(a.sensor.joints.raw_counts == b.sensor.joints.raw_counts);
  CHECK(a.sensor.joints.unwrapped_counts == b.sensor.joints.unwrapped_counts);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(same_bits(a.command.motor[i].duty, b.command.motor[i].duty));
    CHECK(a.command.motor[i].direction_high == b.command.motor[i].direction_high);
  }
  CHECK(same_bits(a.command.torque_N_m, b.command.torque_N_m));
  CHECK(same_bits(a.command.scale, b.command.scale));
  CHECK(a.command.saturated == b.command.saturated);
  CHECK(a.safety.counters.pose_hold_ticks == b.safety.counters.pose_hold_ticks);
  CHECK(a.safety.counters.motor_saturated_ticks == b.safety.counters.motor_saturated_ticks);
  CHECK(a.safety.counters.nonfinite_faults == b.safety.counters.nonfinite_faults);
  CHECK(a.safety.counters.outside_workspace_ticks == b.safety.counters.outside_workspace_ticks);
}

// The scene run on its family's tick and on the general one, over a recorded sweep and
// then readings no sweep gives (far off, unreachable, non-finite).
void check_family_tick_equals_general(const std::string& path, PlanarFamily family) {
  CAPTURE(path);
  const PlanarScene scene = load_planar_environment_file(path);
  REQUIRE(scene.device_model.model.family == family);
  PlanarScene general = load_planar_environment_file(path);
  general.device_model.model.family = PlanarFamily::general;

  std::vector<PlanarReading> readings = record_planar_readings(scene, 4.0);
  REQUIRE(!readings.empty());
  const PlanarReading last = readings.back();
  for (int k = 1; k <= 40; ++k) {
    PlanarReading far = last;
    far.counts[0] += 997 * k;
    far.counts[1] -= 1499 * k;
    far.angle_deg[0] += 9.5 * k;
    far.angle_deg[1] -= 13.25 * k;
    readings.push_back(far);
  }
  PlanarReading bad = last;
  bad.angle_deg[0] = std::numeric_limits<double>::quiet_NaN();
  readings.push_back(bad);
  bad.angle_deg[1] = std::numeric_limits<double>::infinity();
  readings.push_back(bad);
  readings.push_back(last);

  TickStateOf<2> a = make_tick_state(scene);
  TickStateOf<2> b = make_tick_state(general);
  int pushed = 0;
  for (const PlanarReading& reading : readings) {
    step(scene, reading, &a);
    step(general, reading, &b);
    check_same_tick(a, b);
    if (norm(a.effects_force_N) > 0.1) ++pushed;
  }
  CHECK(pushed > 50);  // the sweep met the shape
}

TEST_CASE("planar family tick: the shipped profiles' families") {
  const auto family_of = [](const char* device) {
    const std::string text = std::string(R"({"device": ")") + device + R"(", "effects": []})";
    return load_planar_environment_text(text, device).device_model.model.family;
  };
  CHECK(family_of("haplink") == PlanarFamily::serial_encoders_linear);
  CHECK(family_of("haply2diy_v3") == PlanarFamily::five_bar_angles_torque);
  // Two Hapkits' MR sensors (they wrap) and sqrt duty laws: the general tick.
  CHECK(family_of("hapkit_pantograph") == PlanarFamily::general);
}

TEST_CASE("planar family tick: the Haplink's compiled tick equals the general one to the bit") {
  check_family_tick_equals_general("environments/planar/haplink_box_inside.json", PlanarFamily::serial_encoders_linear);
  check_family_tick_equals_general("environments/planar/haplink_circle_outside.json",
                                   PlanarFamily::serial_encoders_linear);
}

TEST_CASE("planar family tick: the 2DIY v3's compiled tick equals the general one to the bit") {
  check_family_tick_equals_general("environments/planar/haply2diy_v3_box_inside.json",
                                   PlanarFamily::five_bar_angles_torque);
  check_family_tick_equals_general("environments/planar/haply2diy_v3_circle_outside.json",
                                   PlanarFamily::five_bar_angles_torque);
}

}  // namespace
}  // namespace hapscene
