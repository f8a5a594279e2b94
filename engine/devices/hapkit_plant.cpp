#include "engine/devices/hapkit_plant.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/devices/kinematics.hpp"

namespace hapscene {

HapkitPlant::HapkitPlant(const DeviceProfile& profile, const SimulationConfig& config)
    : profile_(profile),
      config_(config),
      hand_(config.hand, config.start_x_m),
      noise_(config.noise_seed),
      x_m_(config.start_x_m) {
  // The MR sensor's home period: where raw counts equal unwrapped counts. (An encoder
  // counts from wherever it starts.)
  const SensorModel& sensor = profile.sensor;
  const double a_m = counts_to_position_m(profile, sensor.min_counts);
  const double b_m = counts_to_position_m(profile, sensor.min_counts + sensor.span_counts - 1);
  const double low_m = std::min(a_m, b_m);
  const double high_m = std::max(a_m, b_m);
  if (sensor.kind == SensorKind::mr && !(config.start_x_m >= low_m && config.start_x_m <= high_m)) {
    // (The start may be the user's, the period is the profile's: the message names both.)
    throw InputError("start position " + format_number(config.start_x_m) + " m is outside the sensor's home period [" +
                     format_number(low_m) + ", " + format_number(high_m) +
                     "] m, where the board starts counting (the period from " +
                     profile_place(profile.source, "/sensor") + ")");
  }
  if (config.substeps_per_tick < 1) throw InputError("substeps per tick must be >= 1");
  stop_damping_N_s_per_m_ =
      2.0 * 0.7 * std::sqrt(profile.plant.end_stop_stiffness_N_per_m * profile.plant.mass_kg);
  last_counts_ = sensor.min_counts;
}

// Sensor: position -> continuous counts (+ noise) -> nearest count -> wrapped into one
// sensor period, as the MR sensor and the 10-bit ADC report it. A position that cannot be
// a reading (non-finite or absurdly far, after a blown-up simulation) is a sensor fault:
// counted, and answered with the last good reading.
std::int32_t HapkitPlant::sensor_counts() noexcept {
  double counts = position_to_counts(profile_, x_m_);
  if (profile_.plant.sensor_noise_counts > 0.0) {
    counts += profile_.plant.sensor_noise_counts * noise_.next();
  }
  if (!(std::abs(counts) < 1e12)) {
    ++sensor_faults_;
    return last_counts_;
  }
  const SensorModel& sensor = profile_.sensor;
  const auto quantized = static_cast<std::int64_t>(std::nearbyint(counts));
  if (sensor.kind == SensorKind::encoder) {
    // A 32-bit counter; a reading beyond it is a fault like the non-finite ones.
    if (quantized < INT32_MIN || quantized > INT32_MAX) {
      ++sensor_faults_;
      return last_counts_;
    }
    last_counts_ = static_cast<std::int32_t>(quantized);
    return last_counts_;
  }
  std::int64_t within = (quantized - sensor.min_counts) % sensor.span_counts;
  if (within < 0) within += sensor.span_counts;
  last_counts_ = static_cast<std::int32_t>(sensor.min_counts + within);
  return last_counts_;
}

double HapkitPlant::stop_force_N(double x_m, double v_m_per_s, double* stiffness, double* damping,
                                 double* stop_m) const noexcept {
  const PlantModel& plant = profile_.plant;
  if (x_m < plant.end_stop_min_m) *stop_m = plant.end_stop_min_m;
  else if (x_m > plant.end_stop_max_m) *stop_m = plant.end_stop_max_m;
  else return *stiffness = *damping = 0.0;
  *stiffness = plant.end_stop_stiffness_N_per_m;
  *damping = stop_damping_N_s_per_m_;
  return *stiffness * (*stop_m - x_m) - *damping * v_m_per_s;
}

double HapkitPlant::coulomb_direction(double driving_N) const noexcept {
  if (v_m_per_s_ != 0.0) return v_m_per_s_ > 0.0 ? 1.0 : -1.0;
  // Stuck: breaks away only when the other forces exceed static friction.
  if (std::abs(driving_N) > profile_.plant.coulomb_N) return driving_N > 0.0 ? 1.0 : -1.0;
  return 0.0;
}

void HapkitPlant::substep(double h_s, double motor_force_N) noexcept {
  hand_.refresh_pointer();
  switch (config_.integrator) {
    case PlantIntegrator::semi_implicit_euler: euler_substep(h_s, motor_force_N); break;
    case PlantIntegrator::rk4: rk4_substep(h_s, motor_force_N); break;
    case PlantIntegrator::exact: exact_substep(h_s, motor_force_N); break;
  }
  // Compensated sum: after 10^9 substeps the clock is still right to the last bit or so
  // (a plain sum drifts by milliseconds, and the hand's motion with it).
  const double add_s = h_s - t_carry_s_;
  const double sum_s = t_s_ + add_s;
  t_carry_s_ = (sum_s - t_s_) - add_s;
  t_s_ = sum_s;
}

// Semi-implicit Euler with stick-slip Coulomb friction: a handle at rest stays at rest
// while the other forces are below the friction force, and a moving handle whose
// velocity would change sign stops for that step.
void HapkitPlant::euler_substep(double h_s, double motor_force_N) noexcept {
  const PlantModel& plant = profile_.plant;
  hand_force_N_ = hand_.force_N(t_s_, x_m_, v_m_per_s_);
  double k = 0.0, c = 0.0, stop_m = 0.0;
  const double stop_N = stop_force_N(x_m_, v_m_per_s_, &k, &c, &stop_m);
  const double driving_N = motor_force_N + hand_force_N_ + stop_N - plant.viscous_N_s_per_m * v_m_per_s_;
  // A gripping hand moves with the handle and adds its mass.
  const double mass_kg = plant.mass_kg + hand_.added_mass_kg(t_s_);

  if (v_m_per_s_ == 0.0) {
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
}

double HapkitPlant::driving_force_N(double t_s, double motor_force_N) const noexcept {
  double k = 0.0, c = 0.0, stop_m = 0.0;
  return motor_force_N + hand_.force_N(t_s, x_m_, v_m_per_s_) + stop_force_N(x_m_, v_m_per_s_, &k, &c, &stop_m) -
         profile_.plant.viscous_N_s_per_m * v_m_per_s_;
}

// Coulomb friction for the higher-order integrators: its direction is fixed while the
// handle moves one way. When the velocity would change sign within the substep, the
// substep is redone up to the moment it reaches zero (estimated linearly), the handle
// stops there, and the rest of the substep starts from rest (stuck, or breaking away the
// other way). `advance(t_s, tau_s, direction)` integrates (x, v) by tau from time t.
template <typename Advance>
void HapkitPlant::advance_with_friction(double h_s, double motor_force_N, Advance advance) noexcept {
  hand_force_N_ = hand_.force_N(t_s_, x_m_, v_m_per_s_);
  double done_s = 0.0;
  double breakaway = 0.0;  // direction of a breakaway found within this substep
  for (int pass = 0; pass < 4 && done_s < h_s; ++pass) {
    const double t_s = t_s_ + done_s;
    const double tau_s = h_s - done_s;
    const double start_N = driving_force_N(t_s, motor_force_N);
    const double direction = breakaway != 0.0 ? breakaway : coulomb_direction(start_N);
    breakaway = 0.0;
    if (direction == 0.0) {
      // Stuck: stays so unless the other forces exceed static friction by the end of the
      // substep; then it breaks away when they reach it (estimated linearly).
      const double end_N = driving_force_N(t_s + tau_s, motor_force_N);
      if (!(std::abs(end_N) > profile_.plant.coulomb_N)) return;
      const double level_N = std::copysign(profile_.plant.coulomb_N, end_N);
      done_s += std::clamp((level_N - start_N) / (end_N - start_N), 0.0, 1.0) * tau_s;
      breakaway = end_N > 0.0 ? 1.0 : -1.0;
      continue;
    }
    const double x0 = x_m_, v0 = v_m_per_s_;
    advance(t_s, tau_s, direction);
    if (v_m_per_s_ * direction >= 0.0 || profile_.plant.coulomb_N == 0.0) return;
    // Reversed: stop where the velocity crosses zero.
    const double to_zero_s = v0 != 0.0 ? tau_s * v0 / (v0 - v_m_per_s_) : 0.0;
    x_m_ = x0;
    v_m_per_s_ = v0;
    if (to_zero_s > 0.0) advance(t_s, to_zero_s, direction);
    v_m_per_s_ = 0.0;
    done_s += to_zero_s;
  }
}

// Classical RK4 on the full force model (hand, end stops, viscous), with Coulomb
// friction's direction fixed while the handle moves one way.
void HapkitPlant::rk4_substep(double h_s, double motor_force_N) noexcept {
  const PlantModel& plant = profile_.plant;
  advance_with_friction(h_s, motor_force_N, [&](double t_s, double tau_s, double direction) noexcept {
    const double mass_kg = plant.mass_kg + hand_.added_mass_kg(t_s);
    const double friction_N = direction * plant.coulomb_N;
    const auto accel = [&](double dt_s, double x_m, double v_m_per_s) noexcept {
      double ks = 0.0, cs = 0.0, xs = 0.0;
      const double f_N = motor_force_N + hand_.force_N(t_s + dt_s, x_m, v_m_per_s) +
                         stop_force_N(x_m, v_m_per_s, &ks, &cs, &xs) -
                         plant.viscous_N_s_per_m * v_m_per_s - friction_N;
      return f_N / mass_kg;
    };
    const double x0 = x_m_, v0 = v_m_per_s_, half = 0.5 * tau_s;
    const double a1 = accel(0.0, x0, v0);
    const double v2 = v0 + half * a1;
    const double a2 = accel(half, x0 + half * v0, v2);
    const double v3 = v0 + half * a2;
    const double a3 = accel(half, x0 + half * v2, v3);
    const double v4 = v0 + tau_s * a3;
    const double a4 = accel(tau_s, x0 + tau_s * v3, v4);
    x_m_ = x0 + tau_s / 6.0 * (v0 + 2.0 * v2 + 2.0 * v3 + v4);
    v_m_per_s_ = v0 + tau_s / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
  });
}

// The exact solution of the linear model frozen at the start: viscous damping, the
// hand's spring-damper toward a reference moving at constant speed over the step, the end stop the
// handle is in (if any), the held motor force and Coulomb friction's constant force.
void HapkitPlant::exact_substep(double h_s, double motor_force_N) noexcept {
  const PlantModel& plant = profile_.plant;
  advance_with_friction(h_s, motor_force_N, [&](double t_s, double tau_s, double direction) noexcept {
    double stop_k = 0.0, stop_c = 0.0, stop_m = 0.0;
    stop_force_N(x_m_, v_m_per_s_, &stop_k, &stop_c, &stop_m);
    LinearModel model;
    model.mass_kg = plant.mass_kg + hand_.added_mass_kg(t_s);
    model.damping_N_s_per_m = plant.viscous_N_s_per_m + stop_c;
    model.stiffness_N_per_m = stop_k;
    model.force_N = motor_force_N - direction * plant.coulomb_N + stop_k * stop_m;
    if (hand_.gripping(t_s)) {
      const HandConfig& hand = config_.hand;
      // The reference as a ramp through its values at both ends of the step, so a corner
      // of the hand's path inside the step costs a second-order error, not a first-order one.
      const double ref_m = hand_.reference_m(t_s);
      const double ref_v = (hand_.reference_m(t_s + tau_s) - ref_m) / tau_s;
      model.stiffness_N_per_m += hand.stiffness_N_per_m;
      model.damping_N_s_per_m += hand.damping_N_s_per_m;
      model.force_N += hand.stiffness_N_per_m * ref_m + hand.damping_N_s_per_m * ref_v;
      model.force_rate_N_per_s = hand.stiffness_N_per_m * ref_v;
    }
    exact_linear_step(model, tau_s, &x_m_, &v_m_per_s_);
  });
}

}  // namespace hapscene
