#pragma once
// A simulated Hapkit that behaves like the real one from the host's side: the host reads
// raw MR sensor counts (quantized, wrapping every sensor period, optionally noisy) and
// writes a PWM duty and a direction pin, held until the next write. The physics live in
// HapkitPlant; this adds the motor driver (PWM resolution, saturation). Deterministic for
// a given seed.
#include <cstdint>

#include "engine/devices/device.hpp"
#include "engine/devices/hapkit_plant.hpp"

namespace hapscene {

class SimulatedHapkit final : public Device, public SimulationTruth {
 public:
  // Throws InputError when the start position is outside the sensor's home period (the
  // host's flip count starts at 0, as a real Hapkit centred at power-up).
  SimulatedHapkit(const DeviceProfile& profile, const SimulationConfig& config);

  std::int32_t read() noexcept override;
  void write(const MotorCommand& command) noexcept override;
  void advance(double dt_s) noexcept override;

  const SimulationTruth* truth() const noexcept override { return this; }
  HandPointerOf<1>* hand_pointer() const noexcept override { return &pointer_; }
  bool deadlines_matter() const noexcept override { return false; }

  // The true plant state, for observers and tests (the host only sees counts).
  double x_m() const noexcept override { return plant_.x_m(); }
  double v_m_per_s() const noexcept override { return plant_.v_m_per_s(); }
  double motor_force_N() const noexcept override { return motor_force_N_; }
  double hand_force_N() const noexcept override { return plant_.hand_force_N(); }
  double hand_target_m() const noexcept override { return plant_.hand_target_m(); }
  double t_s() const noexcept { return plant_.t_s(); }

 private:
  mutable HandPointerOf<1> pointer_;  // a mailbox the live view writes, the plant reads
  HapkitPlant plant_;
  double motor_force_N_{};  // held between writes
};

}  // namespace hapscene
