// The planar device model compiled from a profile: readings to joint angles to the handle
// (round trips within the sensor's quantization, MR unwrapping included), forces to motor
// commands (J^T F by virtual work, the coupling's transpose), saturation scaling that keeps
// the force's direction, the Haplink's linear law and the 2DIY's torque clamp.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "tests/devices/planar_support.hpp"

using namespace hapscene;

namespace {

struct Loaded {
  PlanarProfile profile;
  PlanarModel model;
  Vec2 home_q;
};

// Where the joints are at the start of the sensor's range (see planar_profile_test.cpp).
Vec2 start_angles(const PlanarProfile& profile) {
  Vec2 q{};
  for (int i = 0; i < 2; ++i) {
    const PlanarSensor& s = profile.joints[static_cast<std::size_t>(i)].sensor;
    if (s.kind == PlanarSensorKind::angle) q[i] = s.board_offset_rad + s.offset_rad;
    if (s.kind == PlanarSensorKind::encoder) q[i] = s.offset_rad;
    if (s.kind == PlanarSensorKind::mr) {
      q[i] = (s.min_counts + s.span_counts / 2.0) * s.counts_to_deg_slope * std::numbers::pi / 180.0 + s.offset_rad;
    }
  }
  q[1] += profile.coupling * q[0];
  return q;
}

Loaded load(const std::string& name) {
  Loaded loaded{load_planar_profile(name, "."), {}, {}};
  loaded.model = compile_planar_model(loaded.profile);
  const auto home = test::inverse_kinematics(loaded.profile.linkage, loaded.profile.home_m, start_angles(loaded.profile));
  REQUIRE(home.has_value());
  loaded.home_q = *home;
  return loaded;
}

// The force on the handle that motor torques produce at a pose: tau = joint torques,
// F = J^-T tau.
Vec2 force_from_motors(const PlanarModel& model, const Jacobian2& j, const Vec2& motor_torque_N_m) {
  const Vec2 tau = joint_torques_from_motor_N_m(model, motor_torque_N_m);
  const double det = j.m[0][0] * j.m[1][1] - j.m[0][1] * j.m[1][0];
  // J^T F = tau: [[j00, j10], [j01, j11]] F = tau.
  return Vec2{{(j.m[1][1] * tau[0] - j.m[1][0] * tau[1]) / det, (-j.m[0][1] * tau[0] + j.m[0][0] * tau[1]) / det}};
}

}  // namespace

TEST_CASE("planar model: angles -> readings -> sense gives back the pose within quantization") {
  for (const std::string& name : test::shipped_planar_profiles()) {
    CAPTURE(name);
    const Loaded d = load(name);
    const PlanarWorkspace& w = d.profile.limits.workspace;
    // Walk from home to each corner and the centre in small steps, as a handle moves, so
    // an MR sensor's flips are followed.
    const Vec2 targets[] = {w.box_min_m, w.box_max_m, Vec2{{w.box_min_m[0], w.box_max_m[1]}},
                            Vec2{{w.box_max_m[0], w.box_min_m[1]}}, 0.5 * (w.box_min_m + w.box_max_m)};
    for (const Vec2& target : targets) {
      CAPTURE(target[0]);
      CAPTURE(target[1]);
      const auto goal = test::inverse_kinematics(d.profile.linkage, target, d.home_q);
      REQUIRE(goal.has_value());
      PlanarSensorState state = make_planar_sensor_state(d.model);
      LinkagePose pose;
      const int steps = 2000;
      for (int k = 0; k <= steps; ++k) {
        const Vec2 q = d.home_q + (*goal - d.home_q) * (static_cast<double>(k) / steps);
        pose = sense_planar(d.model, planar_reading_for(d.model, q), &state);
      }
      REQUIRE(pose.valid);
      // Half a count per joint (joint 2 also through the coupling).
      const double r1 = planar_joint_resolution_rad(d.model, 0), r2 = planar_joint_resolution_rad(d.model, 1);
      CHECK(std::fabs(state.q_rad[0] - (*goal)[0]) <= 0.5 * r1 + 1e-12);
      CHECK(std::fabs(state.q_rad[1] - (*goal)[1]) <= 0.5 * r2 + 0.5 * std::fabs(d.model.coupling) * r1 + 1e-12);
      // The position error is at most J times the angle error.
      const LinkagePose truth = solve_linkage(d.profile.linkage, *goal);
      const Jacobian2& j = truth.jacobian;
      const double bound = (std::fabs(j.m[0][0]) + std::fabs(j.m[1][0])) * 0.5 * r1 * (1 + std::fabs(d.model.coupling)) +
                           (std::fabs(j.m[0][1]) + std::fabs(j.m[1][1])) * 0.5 * r2;
      CHECK(norm(pose.handle_m - truth.handle_m) <= bound * 1.01 + 1e-12);
    }
  }
}

TEST_CASE("planar model: a fresh sensor reads the Haplink's course check value at zero counts") {
  const Loaded d = load("haplink");
  PlanarSensorState state = make_planar_sensor_state(d.model);
  const LinkagePose pose = sense_planar(d.model, PlanarReading{}, &state);
  CHECK(pose.handle_m[0] * 1e3 == doctest::Approx(-16.327652).epsilon(1e-7));
  CHECK(pose.handle_m[1] * 1e3 == doctest::Approx(142.337051).epsilon(1e-7));
  // One motor count of joint 1: 2 pi / 48 of the motor, 5.5 / 72 of that at the joint,
  // negative (theta_a = -(R_MA / R_A) theta_ma), and joint 2 follows by the coupling.
  const LinkagePose moved = sense_planar(d.model, PlanarReading{{1, 0}, {}}, &state);
  (void)moved;
  const double joint_1 = -2.0 * std::numbers::pi / 48.0 * 5.5 / 72.0;
  CHECK(state.q_rad[0] == doctest::Approx(joint_1).epsilon(1e-12));
  CHECK(state.q_rad[1] == doctest::Approx(5.5 / 72.0 * joint_1).epsilon(1e-12));
}

TEST_CASE("planar model: motor torques satisfy virtual work (F . dp = motor torque . motor angle)") {
  for (const std::string& name : test::shipped_planar_profiles()) {
    CAPTURE(name);
    const Loaded d = load(name);
    const Vec2 q = d.home_q + Vec2{{0.05, -0.08}};
    const LinkagePose pose = solve_linkage(d.profile.linkage, q);
    REQUIRE(pose.valid);
    const Vec2 force{{0.03, -0.02}};  // small: no motor saturates
    const PlanarMotorCommand command = planar_motor_command(d.model, pose.jacobian, force);
    REQUIRE_FALSE(command.saturated);
    // J^T F against a small joint motion.
    const Vec2 dq{{2e-7, -1.3e-7}};
    const Vec2 dp = solve_linkage(d.profile.linkage, q + dq).handle_m - pose.handle_m;
    const Vec2 tau = joint_torques_N_m(pose.jacobian, force);
    CHECK(dot(force, dp) == doctest::Approx(dot(tau, dq)).epsilon(1e-5));
    // Motor angles (in the direction-pin sense): the sensed joint angle (joint 2 without
    // the coupling) over each motor's ratio and direction.
    const Vec2 d_sensed{{dq[0], dq[1] - d.model.coupling * dq[0]}};
    const Vec2 d_motor{{d_sensed[0] / d.model.joints[0].motor_per_joint_torque,
                        d_sensed[1] / d.model.joints[1].motor_per_joint_torque}};
    CHECK(dot(command.torque_N_m, d_motor) == doctest::Approx(dot(force, dp)).epsilon(1e-5));
    // And back: the torques give the force.
    const Vec2 back = force_from_motors(d.model, pose.jacobian, command.torque_N_m);
    CHECK(back[0] == doctest::Approx(force[0]).epsilon(1e-9));
    CHECK(back[1] == doctest::Approx(force[1]).epsilon(1e-9));
  }
}

TEST_CASE("planar model: the Haplink's encoders and motors agree in sign (virtual work per motor)") {
  // The encoder and the drive of each Haplink motor give the same direction: a motor
  // torque in the direction pin's positive sense turns the motor so its counts grow.
  const Loaded d = load("haplink");
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(d.model.joints[i].rad_per_count * d.model.joints[i].motor_per_joint_torque > 0.0);
  }
}

TEST_CASE("planar model: saturation scales both motors by one factor, keeping the force's direction") {
  for (const std::string& name : test::shipped_planar_profiles()) {
    CAPTURE(name);
    const Loaded d = load(name);
    const LinkagePose pose = solve_linkage(d.profile.linkage, d.home_q);
    for (double angle = 0.0; angle < 2.0 * std::numbers::pi; angle += 0.5) {
      CAPTURE(angle);
      const Vec2 force{{100.0 * std::cos(angle), 100.0 * std::sin(angle)}};
      const PlanarMotorCommand command = planar_motor_command(d.model, pose.jacobian, force);
      CHECK(command.saturated);
      CHECK(command.scale < 1.0);
      CHECK(command.scale > 0.0);
      // The rendered force is the asked one times the scale.
      const Vec2 rendered = force_from_motors(d.model, pose.jacobian, planar_command_torques_N_m(d.model, command));
      CHECK(cross(rendered, force) == doctest::Approx(0.0).scale(1e-9 * dot(force, force)));
      CHECK(dot(rendered, force) > 0.0);
      CHECK(norm(rendered) == doctest::Approx(command.scale * norm(force)).epsilon(1e-9));
      // One motor is at its limit, neither beyond.
      const double use_1 = std::fabs(command.torque_N_m[0]) / d.model.joints[0].motor_torque_max_N_m;
      const double use_2 = std::fabs(command.torque_N_m[1]) / d.model.joints[1].motor_torque_max_N_m;
      CHECK(std::fmax(use_1, use_2) == doctest::Approx(1.0).epsilon(1e-12));
      CHECK(use_1 <= 1.0);
      CHECK(use_2 <= 1.0);
    }
    // Within the drive: no scaling.
    const PlanarMotorCommand small = planar_motor_command(d.model, pose.jacobian, Vec2{{0.01, 0.01}});
    CHECK_FALSE(small.saturated);
    CHECK(small.scale == 1.0);
  }
}

TEST_CASE("planar model: the Haplink's linear duty law (65.13 per N m at the motor)") {
  const Loaded d = load("haplink");
  const LinkagePose pose = solve_linkage(d.profile.linkage, Vec2{});
  const Vec2 force{{0.3, -0.2}};
  const PlanarMotorCommand command = planar_motor_command(d.model, pose.jacobian, force);
  REQUIRE_FALSE(command.saturated);
  // The course's formulas: joint torque = J^T F; motor torque = -(joint torque * R_M / R_sector),
  // here with joint 1's motor also carrying the coupling's share of joint 2.
  const Jacobian2& j = pose.jacobian;
  const double tau_1 = j.m[0][0] * force[0] + j.m[1][0] * force[1];
  const double tau_2 = j.m[0][1] * force[0] + j.m[1][1] * force[1];
  const double ratio = 5.5 / 72.0;
  const double motor_1 = -(tau_1 + ratio * tau_2) * ratio;
  const double motor_2 = -tau_2 * ratio;
  CHECK(command.torque_N_m[0] == doctest::Approx(motor_1).epsilon(1e-12));
  CHECK(command.torque_N_m[1] == doctest::Approx(motor_2).epsilon(1e-12));
  CHECK(command.motor[0].duty == doctest::Approx(std::fabs(motor_1) * 65.13).epsilon(1e-12));
  CHECK(command.motor[1].duty == doctest::Approx(std::fabs(motor_2) * 65.13).epsilon(1e-12));
  CHECK(command.motor[0].direction_high == (motor_1 > 0.0));
  CHECK(command.motor[1].direction_high == (motor_2 > 0.0));
  // Full duty is 1 / 65.13 N m (about 15.4 mN m) at each motor.
  CHECK(d.model.joints[0].motor_torque_max_N_m == doctest::Approx(1.0 / 65.13));
  // The weakest direction at the home pose: the largest force that saturates no motor.
  double weakest_N = std::numeric_limits<double>::infinity();
  for (double angle = 0.0; angle < 2.0 * std::numbers::pi; angle += 0.01) {
    const PlanarMotorCommand c =
        planar_motor_command(d.model, pose.jacobian, Vec2{{100.0 * std::cos(angle), 100.0 * std::sin(angle)}});
    weakest_N = std::fmin(weakest_N, 100.0 * c.scale);
  }
  // Measured 1.345 N (REFERENCE-2D.md derives "about 1.4 N").
  CHECK(weakest_N == doctest::Approx(1.345).epsilon(0.005));
}

TEST_CASE("planar model: the 2DIY's torque command is J^T F, clamped at 0.123 N m") {
  const Loaded d = load("haply2diy_v3");
  const LinkagePose pose = solve_linkage(d.profile.linkage, d.home_q);
  const Vec2 force{{0.4, 0.7}};
  const PlanarMotorCommand command = planar_motor_command(d.model, pose.jacobian, force);
  REQUIRE_FALSE(command.saturated);
  const Vec2 tau = joint_torques_N_m(pose.jacobian, force);
  CHECK(command.torque_N_m[0] == doctest::Approx(tau[0]).epsilon(1e-12));
  CHECK(command.torque_N_m[1] == doctest::Approx(tau[1]).epsilon(1e-12));
  CHECK(command.motor[0].duty == doctest::Approx(std::fabs(tau[0]) / 0.123).epsilon(1e-12));
  // Far beyond: the larger motor torque is exactly the clamp, the other in proportion.
  const PlanarMotorCommand big = planar_motor_command(d.model, pose.jacobian, 50.0 * force);
  CHECK(big.saturated);
  const double larger = std::fmax(std::fabs(big.torque_N_m[0]), std::fabs(big.torque_N_m[1]));
  CHECK(larger == doctest::Approx(0.123).epsilon(1e-12));
  CHECK(big.torque_N_m[0] / big.torque_N_m[1] == doctest::Approx(tau[0] / tau[1]).epsilon(1e-12));
  const Vec2 applied = planar_command_torques_N_m(d.model, big);
  CHECK(applied[0] == big.torque_N_m[0]);
  CHECK(applied[1] == big.torque_N_m[1]);
}

TEST_CASE("planar model: the pantograph's sqrt law and MR unwrapping") {
  const Loaded d = load("hapkit_pantograph");
  const LinkagePose pose = solve_linkage(d.profile.linkage, d.home_q);
  const Vec2 force{{0.5, -0.3}};
  const PlanarMotorCommand command = planar_motor_command(d.model, pose.jacobian, force);
  REQUIRE_FALSE(command.saturated);
  const Vec2 tau = joint_torques_N_m(pose.jacobian, force);
  const double ratio = 4.191 / 73.152;
  CHECK(command.torque_N_m[0] == doctest::Approx(tau[0] * ratio).epsilon(1e-12));
  CHECK(command.torque_N_m[1] == doctest::Approx(-tau[1] * ratio).epsilon(1e-12));  // mirrored joint
  CHECK(command.motor[0].duty == doctest::Approx(std::sqrt(std::fabs(tau[0] * ratio) / 0.03)).epsilon(1e-12));
  const Vec2 applied = planar_command_torques_N_m(d.model, command);
  CHECK(applied[0] == doctest::Approx(command.torque_N_m[0]).epsilon(1e-12));
  CHECK(applied[1] == doctest::Approx(command.torque_N_m[1]).epsilon(1e-12));
  // The MR sensor of joint 1 repeats every 922 counts (about 9.9 deg of the joint): a
  // 30 deg sweep crosses three periods and is followed.
  PlanarSensorState state = make_planar_sensor_state(d.model);
  const Vec2 end = d.home_q + Vec2{{30.0 * std::numbers::pi / 180.0, 0.0}};
  for (int k = 0; k <= 600; ++k) sense_planar(d.model, planar_reading_for(d.model, d.home_q + (end - d.home_q) * (k / 600.0)), &state);
  CHECK(state.flip_counter[0].flips != 0);
  CHECK(state.q_rad[0] == doctest::Approx(end[0]).epsilon(1e-3));
}

TEST_CASE("planar model: a non-finite force commands nothing") {
  const Loaded d = load("haplink");
  const LinkagePose pose = solve_linkage(d.profile.linkage, Vec2{});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const PlanarMotorCommand command = planar_motor_command(d.model, pose.jacobian, Vec2{{nan, 1.0}});
  CHECK(command.torque_N_m[0] == 0.0);
  CHECK(command.torque_N_m[1] == 0.0);
  CHECK(command.motor[0].duty == 0.0);
  CHECK(command.motor[1].duty == 0.0);
  CHECK_FALSE(command.saturated);
}
