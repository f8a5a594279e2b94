#pragma once
// The simulated Hapkit's physics and sensor, driven by a motor force: the handle's
// effective mass, viscous and Coulomb (stick-slip) friction, hard end stops, an optional
// virtual hand, and the MR sensor as the board's ADC sees it (quantized to counts,
// wrapping every sensor period, optionally noisy). Shared by the simulated device (which
// turns the host's command into the force) and the firmware-in-the-loop device (which
// measures the force from the simulated board's PWM pin). Deterministic for a given seed.
#include <cmath>
#include <cstdint>

#include "engine/devices/noise.hpp"
#include "engine/devices/plant_integrators.hpp"
#include "engine/devices/profile.hpp"
#include "engine/devices/virtual_hand.hpp"

namespace hapscene {

struct SimulationConfig {
  double start_x_m{0.0};
  HandConfig hand;
  std::uint64_t noise_seed{1};
  // How the plant is integrated over each tick (see plant_integrators.hpp and docs/explanation/
  // measurements.md: chosen from the accuracy bench's Pareto front).
  PlantIntegrator integrator{PlantIntegrator::exact};
  int substeps_per_tick{2};  // plant integration steps per advance()
};

class HapkitPlant {
 public:
  // Throws InputError when the start position is outside the sensor's home period (the
  // flip count starts at 0, as on a real Hapkit centred at power-up).
  HapkitPlant(const DeviceProfile& profile, const SimulationConfig& config);

  // One integration step of h_s with `motor_force_N` held, by the configured integrator.
  void substep(double h_s, double motor_force_N) noexcept;

  // The sensor reading now: nearest count (plus noise), wrapped into one sensor period.
  std::int32_t sensor_counts() noexcept;

  double x_m() const noexcept { return x_m_; }
  double v_m_per_s() const noexcept { return v_m_per_s_; }
  double t_s() const noexcept { return t_s_; }
  // The live view's pointer takes the hand while active (hand_pointer.hpp).
  void follow(const HandPointerOf<1>* pointer) noexcept { hand_.follow(pointer); }
  double hand_force_N() const noexcept { return hand_force_N_; }
  // Where the hand pulls the handle now; NaN while it does not grip.
  double hand_target_m() const noexcept {
    return hand_.gripping(t_s_) ? hand_.reference_m(t_s_) : std::nan("");  // (a hand of motion none never grips)
  }
  // Sensor readings that could not be formed (a non-finite or absurd position), answered
  // with the last good reading.
  std::uint64_t sensor_faults() const noexcept { return sensor_faults_; }
  const DeviceProfile& profile() const noexcept { return profile_; }
  const SimulationConfig& config() const noexcept { return config_; }

 private:
  // The force of the end stops at (x, v), and the stiffness/damping they add there.
  double stop_force_N(double x_m, double v_m_per_s, double* stiffness, double* damping,
                      double* stop_m) const noexcept;
  // Coulomb friction's sign for this substep (0: stuck, the handle stays put).
  double coulomb_direction(double driving_N) const noexcept;
  // Everything but Coulomb friction on the handle at its current state, at time t.
  double driving_force_N(double t_s, double motor_force_N) const noexcept;
  template <typename Advance>
  void advance_with_friction(double h_s, double motor_force_N, Advance advance) noexcept;
  void euler_substep(double h_s, double motor_force_N) noexcept;
  void rk4_substep(double h_s, double motor_force_N) noexcept;
  void exact_substep(double h_s, double motor_force_N) noexcept;

  DeviceProfile profile_;
  SimulationConfig config_;
  VirtualHand hand_;
  GaussianNoise noise_;
  double x_m_{};
  double v_m_per_s_{};
  double t_s_{};
  double t_carry_s_{};  // rounding error of t_s_ carried to the next step (Kahan)
  double hand_force_N_{};
  double stop_damping_N_s_per_m_{};
  std::int32_t last_counts_{};
  std::uint64_t sensor_faults_{};
};

}  // namespace hapscene
