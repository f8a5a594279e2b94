#pragma once
// Hapkit kinematics, exactly as the board needs them:
//   sensor counts -> sector angle -> handle position, and
//   handle force -> motor torque -> PWM duty and direction pin.
// Sector angle (deg) = slope * counts + offset; handle x = handle_radius * angle (rad).
// Motor torque Tp = pulley_radius / sector_radius * handle_radius * F;
// duty = sqrt(|Tp| / Km) clamped to [0, duty_max]; direction from the sign of F.
#include "engine/devices/profile.hpp"

namespace hapscene {

// What the host sends the motor driver.
struct MotorCommand {
  double duty{};            // [0, duty_max]
  bool direction_high{};    // level of the direction pin
};

double counts_to_position_m(const DeviceProfile& profile, double unwrapped_counts) noexcept;
// Inverse, for the simulated sensor (continuous counts, before quantization).
double position_to_counts(const DeviceProfile& profile, double x_m) noexcept;

MotorCommand force_to_motor(const DeviceProfile& profile, double force_N) noexcept;
// The handle force a command produces (duty taken as given), for the simulator.
double motor_to_force_N(const DeviceProfile& profile, const MotorCommand& command) noexcept;

// The largest handle force the motor can produce at duty_max.
double max_motor_force_N(const DeviceProfile& profile) noexcept;

}  // namespace hapscene
