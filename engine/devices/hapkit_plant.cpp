#include "engine/devices/hapkit_plant.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/errors.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/load/object_reader.hpp"

namespace hapscene {

HapkitPlant::HapkitPlant(const DeviceProfile& profile, const SimulationConfig& config)
    : profile_(profile),
      config_(config),
      hand_(config.hand, config.start_x_m),
      noise_(config.noise_seed),
      x_m_(config.start_x_m) {
  // The sensor's home period: where raw counts equal unwrapped counts.
  const SensorModel& sensor = profile.sensor;
  const double a_m = counts_to_position_m(profile, sensor.min_counts);
  const double b_m = counts_to_position_m(profile, sensor.min_counts + sensor.span_counts - 1);
  const double low_m = std::min(a_m, b_m);
  const double high_m = std::max(a_m, b_m);
  if (!(config.start_x_m >= low_m && config.start_x_m <= high_m)) {
    throw InputError("start position " + format_number(config.start_x_m) +
                     " m is outside the sensor's home period [" + format_number(low_m) + ", " +
                     format_number(high_m) + "] m, where the board starts counting");
  }
  if (config.substeps_per_tick < 1) throw InputError("substeps per tick must be >= 1");
}

// Sensor: position -> continuous counts (+ noise) -> nearest count -> wrapped into one
// sensor period, as the MR sensor and the 10-bit ADC report it.
std::int32_t HapkitPlant::sensor_counts() noexcept {
  double counts = position_to_counts(profile_, x_m_);
  if (profile_.plant.sensor_noise_counts > 0.0) {
    counts += profile_.plant.sensor_noise_counts * noise_.next();
  }
  const SensorModel& sensor = profile_.sensor;
  const auto quantized = static_cast<std::int64_t>(std::nearbyint(counts));
  std::int64_t within = (quantized - sensor.min_counts) % sensor.span_counts;
  if (within < 0) within += sensor.span_counts;
  return static_cast<std::int32_t>(sensor.min_counts + within);
}

// One semi-implicit Euler step of the handle with stick-slip Coulomb friction: a handle
// at rest stays at rest while the other forces are below the friction force, and a
// moving handle whose velocity would change sign stops for that step.
void HapkitPlant::substep(double h_s, double motor_force_N) noexcept {
  const PlantModel& plant = profile_.plant;

  hand_force_N_ = hand_.force_N(t_s_, x_m_, v_m_per_s_);
  double stop_force_N = 0.0;
  const double stop_damping_N_s_per_m =
      2.0 * 0.7 * std::sqrt(plant.end_stop_stiffness_N_per_m * plant.mass_kg);
  if (x_m_ < plant.end_stop_min_m) {
    stop_force_N = plant.end_stop_stiffness_N_per_m * (plant.end_stop_min_m - x_m_) -
                   stop_damping_N_s_per_m * v_m_per_s_;
  } else if (x_m_ > plant.end_stop_max_m) {
    stop_force_N = plant.end_stop_stiffness_N_per_m * (plant.end_stop_max_m - x_m_) -
                   stop_damping_N_s_per_m * v_m_per_s_;
  }
  const double driving_N =
      motor_force_N + hand_force_N_ + stop_force_N - plant.viscous_N_s_per_m * v_m_per_s_;
  // A gripping hand moves with the handle and adds its mass.
  const double mass_kg = plant.mass_kg + hand_.added_mass_kg(t_s_);

  if (v_m_per_s_ == 0.0) {
    // Stuck: breaks away only when the other forces exceed static friction.
    if (std::abs(driving_N) > plant.coulomb_N) {
      const double net_N = driving_N - std::copysign(plant.coulomb_N, driving_N);
      v_m_per_s_ = net_N / mass_kg * h_s;
    }
  } else {
    const double net_N = driving_N - std::copysign(plant.coulomb_N, v_m_per_s_);
    const double v_next = v_m_per_s_ + net_N / mass_kg * h_s;
    v_m_per_s_ = (v_next * v_m_per_s_ < 0.0) ? 0.0 : v_next;
  }
  x_m_ += v_m_per_s_ * h_s;
  t_s_ += h_s;
}

}  // namespace hapscene
