#include "engine/devices/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hapscene {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// Handle force per unit motor torque: F = Tp * sector_radius / (pulley_radius * handle_radius).
double force_per_torque_per_m(const DriveModel& drive) noexcept {
  return drive.sector_radius_m / (drive.pulley_radius_m * drive.handle_radius_m);
}

}  // namespace

double counts_to_position_m(const DeviceProfile& profile, double unwrapped_counts) noexcept {
  const double angle_deg =
      profile.sensor.counts_to_deg_slope * unwrapped_counts + profile.sensor.counts_to_deg_offset;
  return profile.drive.handle_radius_m * angle_deg * kRadPerDeg;
}

double position_to_counts(const DeviceProfile& profile, double x_m) noexcept {
  const double angle_deg = x_m / profile.drive.handle_radius_m / kRadPerDeg;
  return (angle_deg - profile.sensor.counts_to_deg_offset) / profile.sensor.counts_to_deg_slope;
}

MotorCommand force_to_motor(const DeviceProfile& profile, double force_N) noexcept {
  const DriveModel& drive = profile.drive;
  const double torque_N_m = std::abs(force_N) / force_per_torque_per_m(drive);
  MotorCommand command;
  command.duty = std::clamp(std::sqrt(torque_N_m / drive.motor_constant_N_m), 0.0, drive.duty_max);
  command.direction_high = force_N * drive.direction_sign > 0.0;
  return command;
}

double motor_to_force_N(const DeviceProfile& profile, const MotorCommand& command) noexcept {
  const DriveModel& drive = profile.drive;
  const double torque_N_m = drive.motor_constant_N_m * command.duty * command.duty;
  const double magnitude_N = torque_N_m * force_per_torque_per_m(drive);
  const bool positive = command.direction_high == (drive.direction_sign > 0);
  return positive ? magnitude_N : -magnitude_N;
}

double max_motor_force_N(const DeviceProfile& profile) noexcept {
  return motor_to_force_N(profile, MotorCommand{profile.drive.duty_max, profile.drive.direction_sign > 0});
}

}  // namespace hapscene
