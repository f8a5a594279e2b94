#pragma once
// A simulated Hapkit that behaves like the real one from the host's side: the host reads
// raw MR sensor counts (quantized, wrapping every sensor period, optionally noisy) and
// writes a PWM duty and a direction pin, held until the next write. Inside: the handle's
// effective mass, viscous and Coulomb friction, hard end stops, motor saturation and PWM
// resolution, and an optional virtual hand. Deterministic for a given seed.
#include <cstdint>

#include "engine/devices/device.hpp"
#include "engine/devices/noise.hpp"
#include "engine/devices/profile.hpp"
#include "engine/devices/virtual_hand.hpp"

namespace hapscene {

struct SimulationConfig {
  double start_x_m{0.0};
  HandConfig hand;
  std::uint64_t noise_seed{1};
  int substeps_per_tick{10};  // plant integration steps per advance()
};

class SimulatedHapkit final : public Device {
 public:
  // Throws InputError when the start position is outside the sensor's home period (the
  // host's flip count starts at 0, as a real Hapkit centred at power-up).
  SimulatedHapkit(const DeviceProfile& profile, const SimulationConfig& config);

  std::int32_t read_counts() noexcept override;
  void write(const MotorCommand& command) noexcept override;
  void advance(double dt_s) noexcept override;

  // The true plant state, for tests and telemetry (the host only sees counts).
  double x_m() const noexcept { return x_m_; }
  double v_m_per_s() const noexcept { return v_m_per_s_; }
  double t_s() const noexcept { return t_s_; }
  double motor_force_N() const noexcept { return motor_force_N_; }
  double hand_force_N() const noexcept { return hand_force_N_; }

 private:
  void substep(double h_s) noexcept;

  DeviceProfile profile_;
  SimulationConfig config_;
  VirtualHand hand_;
  GaussianNoise noise_;
  double x_m_{};
  double v_m_per_s_{};
  double t_s_{};
  double motor_force_N_{};  // held between writes
  double hand_force_N_{};
};

}  // namespace hapscene
