#include "engine/devices/simulated_hapkit.hpp"

#include <algorithm>
#include <cmath>

#include "engine/devices/kinematics.hpp"

namespace hapscene {

SimulatedHapkit::SimulatedHapkit(const DeviceProfile& profile, const SimulationConfig& config)
    : plant_(profile, config) {
  plant_.follow(&pointer_);
}

std::int32_t SimulatedHapkit::read() noexcept { return plant_.sensor_counts(); }

// Motor: the duty is quantized to the PWM resolution and saturates at full duty; the
// resulting force is held until the next write.
void SimulatedHapkit::write(const MotorCommand& command) noexcept {
  const DeviceProfile& profile = plant_.profile();
  const double levels = profile.drive.pwm_levels;
  MotorCommand applied = command;
  applied.duty = std::nearbyint(std::clamp(command.duty, 0.0, 1.0) * levels) / levels;
  motor_force_N_ = motor_to_force_N(profile, applied);
}

void SimulatedHapkit::advance(double dt_s) noexcept {
  const int substeps = plant_.config().substeps_per_tick;
  const double h_s = dt_s / substeps;
  for (int i = 0; i < substeps; ++i) plant_.substep(h_s, motor_force_N_);
}

}  // namespace hapscene
