#include "engine/devices/kinematics.hpp"

#include <numbers>

namespace hapscene {
namespace {
constexpr double kRadPerDeg = std::numbers::pi / 180.0;
}  // namespace

Kinematics compile_kinematics(const DeviceProfile& profile) noexcept {
  const SensorModel& sensor = profile.sensor;
  const DriveModel& drive = profile.drive;
  Kinematics k;
  k.x_m_per_count = drive.handle_radius_m * sensor.counts_to_deg_slope * kRadPerDeg;
  k.x_m_at_count_zero = drive.handle_radius_m * sensor.counts_to_deg_offset * kRadPerDeg;
  k.torque_N_m_per_N = drive.pulley_radius_m / drive.sector_radius_m * drive.handle_radius_m;
  k.motor_constant_N_m = drive.motor_constant_N_m;
  k.inverse_motor_constant = 1.0 / drive.motor_constant_N_m;
  k.duty_max = drive.duty_max;
  k.direction_sign = drive.direction_sign;
  k.duty_law = drive.duty_law;
  return k;
}

double counts_to_position_m(const DeviceProfile& profile, double unwrapped_counts) noexcept {
  return counts_to_position_m(compile_kinematics(profile), unwrapped_counts);
}

MotorCommand force_to_motor(const DeviceProfile& profile, double force_N) noexcept {
  return force_to_motor(compile_kinematics(profile), force_N);
}

double position_to_counts(const DeviceProfile& profile, double x_m) noexcept {
  const Kinematics k = compile_kinematics(profile);
  return (x_m - k.x_m_at_count_zero) / k.x_m_per_count;
}

double motor_to_force_N(const DeviceProfile& profile, const MotorCommand& command) noexcept {
  const Kinematics k = compile_kinematics(profile);
  const double torque_N_m = k.duty_law == DutyLaw::sqrt ? k.motor_constant_N_m * command.duty * command.duty
                                                       : k.motor_constant_N_m * command.duty;
  const double magnitude_N = torque_N_m / k.torque_N_m_per_N;
  const bool positive = command.direction_high == (k.direction_sign > 0);
  return positive ? magnitude_N : -magnitude_N;
}

double max_motor_force_N(const DeviceProfile& profile) noexcept {
  return motor_to_force_N(profile, MotorCommand{profile.drive.duty_max, profile.drive.direction_sign > 0});
}

}  // namespace hapscene
