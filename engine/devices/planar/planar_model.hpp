#pragma once
// The device-specific half of a 2-DOF tick, compiled from a planar profile (the 1-DOF twin
// is engine/devices/device_model.hpp):
//   sense:   raw readings per joint (counts, or the board's angles) -> joint angles q (rad)
//            -> solve_linkage -> the handle position and the Jacobian at that pose;
//   command: a task-space force F at that pose -> joint torques J^T F -> motor torques
//            (the coupling's transpose, the capstan ratio, the direction) -> per motor the
//            duty and direction pin, or a torque in N m. When a motor would exceed what its
//            drive gives, both motor torques scale by the same factor, so the force keeps
//            its direction, and the command says so (the caller counts it).
// Inline, no allocation, no exceptions: both run inside the tick.
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "engine/base/axes.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/devices/planar/linkage.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "protocol/flip_counter.hpp"

namespace hapscene {

// One joint's sensor and motor, combined into the constants a tick uses.
struct PlanarJointModel {
  bool reads_angle{};           // the board reports degrees (else counts)
  bool unwraps{};               // an MR sensor's wrapping counts
  std::int32_t flip_threshold_counts{};
  std::int32_t span_counts{};
  std::int32_t min_counts{};
  double rad_per_count{};       // counts to the joint's sensed angle (signed)
  double offset_rad{};          // sensed angle at count 0 (or added to the board's angle)
  double counts_per_revolution{};  // angle: the board's resolution (for quantizing)
  // Drive
  PlanarDriveLaw law{PlanarDriveLaw::linear};
  double motor_per_joint_torque{};  // direction_sign * transmission ratio
  double motor_torque_max_N_m{};    // the largest motor torque the drive gives
  double duty_per_N_m{};            // linear
  double inverse_motor_constant{};  // sqrt: 1 / Km
  double motor_constant_N_m{};      // sqrt: Km
  double duty_max{1.0};
};

// The device families whose tick is compiled with their sensors, linkage and drive laws
// known (the stages' per-joint and per-law branches decided at compile time); a model of
// any other make runs the general tick. compile_planar_model names the family; the scene's
// tick chooses its compiled variant once per tick from it (step.cpp).
enum class PlanarFamily : std::uint8_t {
  general,
  serial_encoders_linear,  // a serial arm read by encoders (no wrap), linear duty laws (the Haplink)
  five_bar_angles_torque,  // a five-bar whose board reports angles and takes torques (the 2DIY)
};

// A planar profile compiled for the tick: immutable, read through a const reference.
struct PlanarModel {
  Linkage linkage;
  std::array<PlanarJointModel, 2> joints{};
  double coupling{};  // q2 = sensed_2 + coupling * q1
  PlanarFamily family{PlanarFamily::general};
};

// The family of a compiled model (from its linkage, sensors and drive laws).
PlanarFamily planar_family_of(const PlanarModel& model) noexcept;

PlanarModel compile_planar_model(const PlanarProfile& profile) noexcept;

// What the device reads for both joints: counts (MR, encoder) or angles in degrees (a
// board that reports angles); each joint uses the one its sensor gives.
struct PlanarReading {
  std::array<std::int32_t, 2> counts{};
  Vec2 angle_deg{};
};

// The sensor stage's state for one run (per joint flip counters, for MR sensors).
struct PlanarSensorState {
  std::array<FlipCounter, 2> flip_counter{};
  std::array<std::int32_t, 2> raw_counts{};
  std::array<std::int32_t, 2> unwrapped_counts{};
  Vec2 q_rad{};  // the latest joint angles
};

// A fresh sensor stage for a run (an encoder's counter is set never to flip).
PlanarSensorState make_planar_sensor_state(const PlanarModel& model) noexcept;

// Sensor stage: raw readings to joint angles (kept in `state->q_rad`), then the pose,
// written to `pose`.
// kFamily: the model's family (general: decided from the model's fields).
template <PlanarFamily kFamily = PlanarFamily::general>
[[gnu::always_inline]] inline void sense_planar(const PlanarModel& model, const PlanarReading& reading,
                                                PlanarSensorState* state, LinkagePose* pose) noexcept {
  Vec2 q{};
  for (int i = 0; i < 2; ++i) {
    const PlanarJointModel& joint = model.joints[static_cast<std::size_t>(i)];
    const bool reads_angle =
        kFamily == PlanarFamily::general ? joint.reads_angle : kFamily == PlanarFamily::five_bar_angles_torque;
    const bool unwraps = kFamily == PlanarFamily::general && joint.unwraps;
    if (reads_angle) {
      q[i] = reading.angle_deg[i] * (std::numbers::pi / 180.0) + joint.offset_rad;
    } else {
      // Only an MR sensor wraps: an encoder's count is already unwrapped (its flip
      // counter could never flip), so it skips the counter's work.
      const std::size_t k = static_cast<std::size_t>(i);
      const std::int32_t raw = reading.counts[k];
      const std::int32_t unwrapped = unwraps ? state->flip_counter[k].update(raw) : raw;
      state->raw_counts[k] = raw;
      state->unwrapped_counts[k] = unwrapped;
      q[i] = joint.rad_per_count * unwrapped + joint.offset_rad;
    }
  }
  q[1] += model.coupling * q[0];
  state->q_rad = q;
  if constexpr (kFamily == PlanarFamily::general) {
    solve_linkage(model.linkage, q, pose);
  } else if (!all_finite(q)) {
    *pose = LinkagePose{};
  } else if constexpr (kFamily == PlanarFamily::serial_encoders_linear) {
    solve_serial(model.linkage.serial, q, pose);
  } else {
    solve_five_bar(model.linkage.five_bar, q, pose);
  }
}
inline LinkagePose sense_planar(const PlanarModel& model, const PlanarReading& reading,
                                PlanarSensorState* state) noexcept {
  LinkagePose pose;
  sense_planar<>(model, reading, state, &pose);
  return pose;
}

// What the host sends both motors, and what happened on the way.
struct PlanarMotorCommand {
  std::array<MotorCommand, 2> motor{};  // duty and direction pin per motor (torque law: duty
                                        // is the fraction of the clamp, for logs)
  Vec2 torque_N_m{};    // motor torques after scaling, signed as the direction pin (the
                        // torque law's command)
  double scale{1.0};    // the common factor applied to both (1: none)
  bool saturated{};     // a motor needed more than its drive gives: both were scaled
};

// Motor `i` of the command (kinematics.hpp's motor_of, for two motors).
constexpr const MotorCommand& motor_of(const PlanarMotorCommand& command, int i) noexcept {
  return command.motor[static_cast<std::size_t>(i)];
}

// Joint torques (tau = J^T F) to motor torques: the coupling's transpose (virtual work:
// q2 depends on q1, so joint 1's motor also carries coupling * tau2), then per motor the
// ratio and the direction.
inline Vec2 motor_torques_from_joint_N_m(const PlanarModel& model, const Vec2& joint_torque_N_m) noexcept {
  const double through_1 = joint_torque_N_m[0] + model.coupling * joint_torque_N_m[1];
  return Vec2{{model.joints[0].motor_per_joint_torque * through_1,
               model.joints[1].motor_per_joint_torque * joint_torque_N_m[1]}};
}

// The inverse, for a simulated plant: the joint torques the motor torques produce.
inline Vec2 joint_torques_from_motor_N_m(const PlanarModel& model, const Vec2& motor_torque_N_m) noexcept {
  const double tau_2 = motor_torque_N_m[1] / model.joints[1].motor_per_joint_torque;
  const double through_1 = motor_torque_N_m[0] / model.joints[0].motor_per_joint_torque;
  return Vec2{{through_1 - model.coupling * tau_2, tau_2}};
}

// Both motor torques scaled by the one factor that brings each within its drive (the
// limiting motor lands on its limit, never past it); out of line, as it is rare.
[[gnu::noinline]] void scale_to_drives(const PlanarModel& model, Vec2* torque_N_m,
                                       PlanarMotorCommand* command) noexcept;

// Command stage: the force on the handle at the pose whose Jacobian is `jacobian`, written
// to `command`. kFamily as for sense_planar.
template <PlanarFamily kFamily = PlanarFamily::general>
[[gnu::always_inline]] inline void planar_motor_command(const PlanarModel& model, const Jacobian2& jacobian,
                                                        const Vec2& force_N, PlanarMotorCommand* out) noexcept {
  PlanarMotorCommand& command = *out;
  command.scale = 1.0;
  command.saturated = false;
  Vec2 torque = motor_torques_from_joint_N_m(model, joint_torques_N_m(jacobian, force_N));
  if (!all_finite(torque)) torque = Vec2{};
  // The common case in two comparisons: both motors within their drives (NaN cannot be).
  if (!(std::fabs(torque[0]) <= model.joints[0].motor_torque_max_N_m &&
        std::fabs(torque[1]) <= model.joints[1].motor_torque_max_N_m)) [[unlikely]] {
    scale_to_drives(model, &torque, &command);
  }
  command.torque_N_m = torque;
  for (int i = 0; i < 2; ++i) {
    const PlanarJointModel& joint = model.joints[static_cast<std::size_t>(i)];
    MotorCommand& motor = command.motor[static_cast<std::size_t>(i)];
    const double magnitude = std::fabs(torque[i]);
    const PlanarDriveLaw law = kFamily == PlanarFamily::general                  ? joint.law
                               : kFamily == PlanarFamily::serial_encoders_linear ? PlanarDriveLaw::linear
                                                                                 : PlanarDriveLaw::torque;
    double duty;
    if (law == PlanarDriveLaw::linear) {
      duty = magnitude * joint.duty_per_N_m;
    } else if (law == PlanarDriveLaw::sqrt) {
      duty = std::sqrt(magnitude * joint.inverse_motor_constant);
    } else {
      duty = magnitude / joint.motor_torque_max_N_m;
    }
    // Rounding at the limit: never above the drive's maximum (the torque law's is 1).
    // (Written out: std::fmin is a library call, and neither can be NaN here.)
    motor.duty = duty < joint.duty_max ? duty : joint.duty_max;
    motor.direction_high = torque[i] > 0.0;
  }
}
inline PlanarMotorCommand planar_motor_command(const PlanarModel& model, const Jacobian2& jacobian,
                                               const Vec2& force_N) noexcept {
  PlanarMotorCommand command;
  planar_motor_command(model, jacobian, force_N, &command);
  return command;
}

// For a simulated plant and tests: the motor torques a command produces (duty laws: from
// duty and pin; the torque law: the torque, clamped as the board does).
Vec2 planar_command_torques_N_m(const PlanarModel& model, const PlanarMotorCommand& command) noexcept;

// For a simulated sensor and tests: what the device reads at joint angles q, quantized as
// the sensor is (rounded to a count, or to the board's 360 / counts_per_revolution deg);
// MR counts wrap into the sensor's period [min, min + span).
PlanarReading planar_reading_for(const PlanarModel& model, const Vec2& q_rad) noexcept;

// The sensed angle of one count (rad): the sensor's resolution at the joint.
double planar_joint_resolution_rad(const PlanarModel& model, int joint) noexcept;

}  // namespace hapscene
