#pragma once
// Hapkit kinematics, exactly as the board needs them:
//   sensor counts -> sector angle -> handle position, and
//   handle force -> motor torque -> PWM duty and direction pin.
// Sector angle (deg) = slope * counts + offset; handle x = handle_radius * angle (rad).
// Motor torque Tp = pulley_radius / sector_radius * handle_radius * F;
// duty = sqrt(|Tp| / Km) (the Hapkit's law) or |Tp| / Km (a linear driver), clamped to
// [0, duty_max]; direction from the sign of F.
//
// The constants are combined once (compile_kinematics), so a tick multiplies and never
// divides.
#include <algorithm>
#include <cmath>

#include "engine/devices/profile.hpp"

namespace hapscene {

// What the host sends the motor driver.
struct MotorCommand {
  double duty{};            // [0, duty_max]
  bool direction_high{};    // level of the direction pin
};

// Motor `i` of a command; a one-motor command is its own motor 0. Code written over N reads
// each motor of a DeviceIo<N>::Command so (the planar command's overload: planar_model.hpp).
constexpr const MotorCommand& motor_of(const MotorCommand& command, int /*i*/) noexcept { return command; }

// A profile's kinematics, combined into the few constants a tick uses.
struct Kinematics {
  double x_m_per_count{};           // handle_radius * slope * pi / 180
  double x_m_at_count_zero{};       // handle_radius * offset * pi / 180
  double torque_N_m_per_N{};        // pulley_radius / sector_radius * handle_radius
  double motor_constant_N_m{};      // Km
  double inverse_motor_constant{};  // 1 / Km
  double duty_max{};
  int direction_sign{1};
  DutyLaw duty_law{DutyLaw::sqrt};
};

Kinematics compile_kinematics(const DeviceProfile& profile) noexcept;

inline double counts_to_position_m(const Kinematics& k, double unwrapped_counts) noexcept {
  return k.x_m_per_count * unwrapped_counts + k.x_m_at_count_zero;
}

inline MotorCommand force_to_motor(const Kinematics& k, double force_N) noexcept {
  const double torque_N_m = k.torque_N_m_per_N * std::abs(force_N);
  MotorCommand command;
  const double duty_at_full_range = torque_N_m * k.inverse_motor_constant;
  const double duty = k.duty_law == DutyLaw::sqrt ? std::sqrt(duty_at_full_range) : duty_at_full_range;
  command.duty = std::min(duty, k.duty_max);
  command.direction_high = force_N * k.direction_sign > 0.0;
  return command;
}

// The same from a profile (for tests and tools; a tick uses the compiled form).
double counts_to_position_m(const DeviceProfile& profile, double unwrapped_counts) noexcept;
MotorCommand force_to_motor(const DeviceProfile& profile, double force_N) noexcept;

// Inverse of counts_to_position_m, for the simulated sensor (continuous counts).
double position_to_counts(const DeviceProfile& profile, double x_m) noexcept;
// The handle force a command produces (duty taken as given), for the simulator.
double motor_to_force_N(const DeviceProfile& profile, const MotorCommand& command) noexcept;
// The largest handle force the motor can produce at duty_max.
double max_motor_force_N(const DeviceProfile& profile) noexcept;

}  // namespace hapscene
