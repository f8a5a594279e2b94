#include "engine/devices/planar/planar_model.hpp"

#include <climits>
#include <cmath>
#include <numbers>

namespace hapscene {

PlanarModel compile_planar_model(const PlanarProfile& profile) noexcept {
  PlanarModel model;
  model.linkage = profile.linkage;
  model.coupling = profile.coupling;
  for (std::size_t i = 0; i < 2; ++i) {
    const PlanarJoint& joint = profile.joints[i];
    PlanarJointModel& out = model.joints[i];
    const PlanarSensor& sensor = joint.sensor;
    out.reads_angle = sensor.kind == PlanarSensorKind::angle;
    out.unwraps = sensor.kind == PlanarSensorKind::mr;
    out.offset_rad = sensor.offset_rad;
    out.counts_per_revolution = sensor.counts_per_revolution;
    if (sensor.kind == PlanarSensorKind::mr) {
      // The MR sensor's calibration is of the joint (the Hapkit's sector) itself.
      out.rad_per_count = sensor.counts_to_deg_slope * std::numbers::pi / 180.0;
      out.flip_threshold_counts = sensor.flip_threshold_counts;
      out.span_counts = sensor.span_counts;
      out.min_counts = sensor.min_counts;
    } else if (sensor.kind == PlanarSensorKind::encoder) {
      // On the motor shaft: a motor turn is transmission_ratio of a joint turn.
      out.rad_per_count = sensor.direction_sign * 2.0 * std::numbers::pi / sensor.counts_per_revolution *
                          joint.transmission_ratio;
    }
    const PlanarDrive& drive = joint.drive;
    out.law = drive.law;
    out.motor_per_joint_torque = drive.direction_sign * joint.transmission_ratio;
    out.duty_max = drive.duty_max;
    switch (drive.law) {
      case PlanarDriveLaw::sqrt:
        out.motor_constant_N_m = drive.motor_constant_N_m;
        out.inverse_motor_constant = 1.0 / drive.motor_constant_N_m;
        out.motor_torque_max_N_m = drive.motor_constant_N_m * drive.duty_max * drive.duty_max;
        break;
      case PlanarDriveLaw::linear:
        out.duty_per_N_m = drive.duty_per_N_m;
        out.motor_torque_max_N_m = drive.duty_max / drive.duty_per_N_m;
        break;
      case PlanarDriveLaw::torque:
        out.duty_max = 1.0;
        out.motor_torque_max_N_m = drive.torque_max_N_m;
        break;
    }
  }
  model.family = planar_family_of(model);
  return model;
}

PlanarFamily planar_family_of(const PlanarModel& model) noexcept {
  const PlanarJointModel& j1 = model.joints[0];
  const PlanarJointModel& j2 = model.joints[1];
  const bool encoders = !j1.reads_angle && !j2.reads_angle && !j1.unwraps && !j2.unwraps;
  const bool angles = j1.reads_angle && j2.reads_angle;
  const bool linear = j1.law == PlanarDriveLaw::linear && j2.law == PlanarDriveLaw::linear;
  const bool torque = j1.law == PlanarDriveLaw::torque && j2.law == PlanarDriveLaw::torque;
  if (model.linkage.family == LinkageFamily::serial_2r && encoders && linear) {
    return PlanarFamily::serial_encoders_linear;
  }
  if (model.linkage.family == LinkageFamily::five_bar && angles && torque) {
    return PlanarFamily::five_bar_angles_torque;
  }
  return PlanarFamily::general;
}

PlanarSensorState make_planar_sensor_state(const PlanarModel& model) noexcept {
  PlanarSensorState state;
  for (std::size_t i = 0; i < 2; ++i) {
    const PlanarJointModel& joint = model.joints[i];
    // As for the 1-DOF encoder (device_model.cpp): a threshold no jump exceeds, a span of 0.
    state.flip_counter[i].threshold_counts = joint.unwraps ? joint.flip_threshold_counts : INT32_MAX;
    state.flip_counter[i].span_counts = joint.unwraps ? joint.span_counts : 0;
  }
  return state;
}

void scale_to_drives(const PlanarModel& model, Vec2* torque_N_m, PlanarMotorCommand* command) noexcept {
  Vec2& torque = *torque_N_m;
  // One factor for both motors: the smallest that brings each within its drive.
  double scale = 1.0;
  for (int i = 0; i < 2; ++i) {
    const double needed = std::fabs(torque[i]);
    const double available = model.joints[static_cast<std::size_t>(i)].motor_torque_max_N_m;
    if (needed > available) scale = std::fmin(scale, available / needed);
  }
  if (scale < 1.0) {
    torque *= scale;
    // The limiting motor lands on its limit up to rounding: never past it.
    for (int i = 0; i < 2; ++i) {
      const double available = model.joints[static_cast<std::size_t>(i)].motor_torque_max_N_m;
      torque[i] = std::fmax(-available, std::fmin(torque[i], available));
    }
    command->saturated = true;
    command->scale = scale;
  }
}

Vec2 planar_command_torques_N_m(const PlanarModel& model, const PlanarMotorCommand& command) noexcept {
  Vec2 torque{};
  for (int i = 0; i < 2; ++i) {
    const PlanarJointModel& joint = model.joints[static_cast<std::size_t>(i)];
    const MotorCommand& motor = command.motor[static_cast<std::size_t>(i)];
    double magnitude;
    switch (joint.law) {
      case PlanarDriveLaw::sqrt: magnitude = joint.motor_constant_N_m * motor.duty * motor.duty; break;
      case PlanarDriveLaw::linear: magnitude = motor.duty / joint.duty_per_N_m; break;
      default: {
        const double t = std::fmax(-joint.motor_torque_max_N_m, std::fmin(command.torque_N_m[i], joint.motor_torque_max_N_m));
        torque[i] = std::isfinite(t) ? t : 0.0;
        continue;
      }
    }
    torque[i] = motor.direction_high ? magnitude : -magnitude;
  }
  return torque;
}

PlanarReading planar_reading_for(const PlanarModel& model, const Vec2& q_rad) noexcept {
  PlanarReading reading;
  // The sensors see joint 2 before the coupling.
  const Vec2 sensed{{q_rad[0], q_rad[1] - model.coupling * q_rad[0]}};
  for (int i = 0; i < 2; ++i) {
    const PlanarJointModel& joint = model.joints[static_cast<std::size_t>(i)];
    if (joint.reads_angle) {
      const double step_deg = 360.0 / joint.counts_per_revolution;
      const double angle_deg = (sensed[i] - joint.offset_rad) * 180.0 / std::numbers::pi;
      reading.angle_deg[i] = std::round(angle_deg / step_deg) * step_deg;
      continue;
    }
    double counts = std::round((sensed[i] - joint.offset_rad) / joint.rad_per_count);
    if (joint.unwraps) {
      const double span = joint.span_counts;
      counts = joint.min_counts + std::fmod(std::fmod(counts - joint.min_counts, span) + span, span);
    }
    counts = std::fmax(static_cast<double>(INT32_MIN), std::fmin(counts, static_cast<double>(INT32_MAX)));
    reading.counts[static_cast<std::size_t>(i)] = std::isfinite(counts) ? static_cast<std::int32_t>(counts) : 0;
  }
  return reading;
}

double planar_joint_resolution_rad(const PlanarModel& model, int joint) noexcept {
  const PlanarJointModel& j = model.joints[static_cast<std::size_t>(joint)];
  return j.reads_angle ? 2.0 * std::numbers::pi / j.counts_per_revolution : std::fabs(j.rad_per_count);
}

}  // namespace hapscene
