#pragma once
// What the haptic loop needs of a device: a raw sensor reading and a motor command.
// Simulated devices also advance their physics by one tick period.
#include <cstdint>

#include "engine/devices/kinematics.hpp"

namespace hapscene {

class Device {
 public:
  virtual ~Device() = default;
  // The raw sensor reading (ADC counts of the MR sensor), as the board reports it.
  virtual std::int32_t read_counts() noexcept = 0;
  // The motor command, held until the next write (sample-and-hold).
  virtual void write(const MotorCommand& command) noexcept = 0;
  // Lets `dt_s` of device time pass. Real devices move on their own and ignore it.
  virtual void advance(double dt_s) noexcept { (void)dt_s; }
};

}  // namespace hapscene
