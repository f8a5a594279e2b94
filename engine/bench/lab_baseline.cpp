#include "engine/bench/lab_baseline.hpp"

#include <cmath>

namespace hapscene {
namespace {

// Sensor part of the sketch: flip counting on the raw reading, then the linear fit.
inline double sketch_position_m(const LabBaselineConstants& c, std::int32_t raw,
                                LabBaselineState* s) noexcept {
  if (s->started) {
    const std::int32_t jump = raw - s->last_raw;
    if (jump > c.flip_threshold_counts) s->flips--;
    else if (jump < -c.flip_threshold_counts) s->flips++;
  }
  s->started = true;
  s->last_raw = raw;
  const double updated_pos = raw + s->flips * c.span_counts;
  const double theta_deg = c.slope_deg_per_count * updated_pos + c.offset_deg;
  return c.handle_radius_m * theta_deg * 3.14159265358979323846 / 180.0;
}

// The sketch's velocity: 0.9 of the new difference over the period plus 0.1 of the
// previous difference.
inline double sketch_velocity(const LabBaselineConstants& c, double xh, LabBaselineState* s) noexcept {
  const double dxh = (xh - s->last_x_m) / c.period_s;
  const double filtered = 0.9 * dxh + 0.1 * s->last_dxh_m_per_s;
  s->last_x_m = xh;
  s->last_dxh_m_per_s = dxh;
  return filtered;
}

// Motor part of the sketch: torque, duty = sqrt(|Tp| / Km) capped at 1, direction pin.
inline void sketch_output(const LabBaselineConstants& c, double force, LabBaselineState* s) noexcept {
  const double tp = c.pulley_radius_m / c.sector_radius_m * c.handle_radius_m * force;
  s->direction_high = force > 0;
  double duty = std::sqrt(std::fabs(tp) / c.motor_constant_N_m);
  if (duty > 1) duty = 1;
  s->duty = duty;
}

}  // namespace

// The spring and the wall do not use the velocity, but the sketch computes it every loop
// whatever the force law, and so do these.
void lab_spring_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept {
  const double xh = sketch_position_m(c, raw, s);
  s->velocity_m_per_s = sketch_velocity(c, xh, s);
  sketch_output(c, -c.stiffness_N_per_m * (xh - c.position_m), s);
}

void lab_wall_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept {
  const double xh = sketch_position_m(c, raw, s);
  s->velocity_m_per_s = sketch_velocity(c, xh, s);
  double force = 0;
  if (c.solid_above ? xh > c.position_m : xh < c.position_m) force = -c.stiffness_N_per_m * (xh - c.position_m);
  sketch_output(c, force, s);
}

void lab_damper_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept {
  const double xh = sketch_position_m(c, raw, s);
  const double dxh = sketch_velocity(c, xh, s);
  sketch_output(c, -c.damping_N_s_per_m * dxh, s);
}

void lab_texture_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept {
  const double xh = sketch_position_m(c, raw, s);
  const double dxh = sketch_velocity(c, xh, s);
  const double period = c.width_m + c.spacing_m;
  const double phase = c.mirror ? std::fabs(xh - c.offset_m) : xh - c.offset_m;  // the lab's |x|
  const double within = std::fmod(std::fmod(phase, period) + period, period);
  sketch_output(c, within < c.width_m ? -c.damping_N_s_per_m * dxh : 0.0, s);
}

// ---- The folded floor ------------------------------------------------------------------

LabFoldedConstants fold_lab_constants(const LabBaselineConstants& c) {
  constexpr double kPi = 3.14159265358979323846;
  LabFoldedConstants f;
  f.m_per_count = c.handle_radius_m * c.slope_deg_per_count * kPi / 180.0;
  f.offset_m = c.handle_radius_m * c.offset_deg * kPi / 180.0;
  f.flip_threshold_counts = c.flip_threshold_counts;
  f.span_counts = c.span_counts;
  f.new_difference_per_m = 0.9 / c.period_s;
  f.duty_squared_per_N = c.pulley_radius_m / c.sector_radius_m * c.handle_radius_m / c.motor_constant_N_m;
  f.stiffness_N_per_m = c.stiffness_N_per_m;
  f.position_m = c.position_m;
  f.solid_above = c.solid_above;
  f.damping_N_s_per_m = c.damping_N_s_per_m;
  f.width_m = c.width_m;
  f.period_m = c.width_m + c.spacing_m;
  f.per_period = 1.0 / f.period_m;
  f.texture_offset_m = c.offset_m;
  f.mirror = c.mirror;
  return f;
}

namespace {

inline double folded_position_m(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept {
  const std::int32_t jump = raw - s->last_raw;
  s->flips += s->started ? (jump < -f.flip_threshold_counts) - (jump > f.flip_threshold_counts) : 0;
  s->started = true;
  s->last_raw = raw;
  return f.m_per_count * static_cast<double>(raw + s->flips * f.span_counts) + f.offset_m;
}

// 0.9 of the new difference over the period plus 0.1 of the previous one (kept pre-scaled).
inline double folded_velocity(const LabFoldedConstants& f, double x_m, LabBaselineState* s) noexcept {
  const double scaled_new = f.new_difference_per_m * (x_m - s->last_x_m);
  const double v = scaled_new + s->last_dxh_m_per_s;
  s->last_x_m = x_m;
  s->last_dxh_m_per_s = scaled_new * (0.1 / 0.9);
  return v;
}

inline void folded_output(const LabFoldedConstants& f, double force_N, LabBaselineState* s) noexcept {
  s->direction_high = force_N > 0;
  s->duty = std::fmin(std::sqrt(std::fabs(force_N) * f.duty_squared_per_N), 1.0);
}

}  // namespace

void lab_spring_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept {
  folded_output(f, f.stiffness_N_per_m * (f.position_m - folded_position_m(f, raw, s)), s);
}

void lab_wall_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept {
  const double x_m = folded_position_m(f, raw, s);
  const bool inside = f.solid_above ? x_m > f.position_m : x_m < f.position_m;
  folded_output(f, inside ? f.stiffness_N_per_m * (f.position_m - x_m) : 0.0, s);
}

void lab_damper_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept {
  folded_output(f, -f.damping_N_s_per_m * folded_velocity(f, folded_position_m(f, raw, s), s), s);
}

void lab_texture_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept {
  const double x_m = folded_position_m(f, raw, s);
  const double v = folded_velocity(f, x_m, s);
  const double phase = f.mirror ? std::fabs(x_m - f.texture_offset_m) : x_m - f.texture_offset_m;
  const double within = phase - f.period_m * std::floor(phase * f.per_period);
  folded_output(f, within < f.width_m ? -f.damping_N_s_per_m * v : 0.0, s);
}

bool lab_baseline_for(const Scene& scene, LabBaselineKind* kind, LabBaselineConstants* constants) {
  if (scene.effects.size() != 1) return false;
  LabBaselineConstants& c = *constants;
  c = LabBaselineConstants{};
  c.slope_deg_per_count = scene.device.sensor.counts_to_deg_slope;
  c.offset_deg = scene.device.sensor.counts_to_deg_offset;
  c.flip_threshold_counts = scene.device.sensor.flip_threshold_counts;
  c.span_counts = scene.device.sensor.span_counts;
  c.handle_radius_m = scene.device.drive.handle_radius_m;
  c.pulley_radius_m = scene.device.drive.pulley_radius_m;
  c.sector_radius_m = scene.device.drive.sector_radius_m;
  c.motor_constant_N_m = scene.device.drive.motor_constant_N_m;
  c.period_s = scene.period_s;
  const Effect& effect = scene.effects[0];
  if (const auto* spring = std::get_if<Spring>(&effect)) {
    *kind = LabBaselineKind::spring;
    c.stiffness_N_per_m = spring->stiffness_N_per_m;
    c.position_m = spring->center_m;
  } else if (const auto* wall = std::get_if<Wall>(&effect)) {
    *kind = LabBaselineKind::wall;
    c.stiffness_N_per_m = wall->stiffness_N_per_m;
    c.position_m = wall->position_m;
    c.solid_above = wall->solid_above;
  } else if (const auto* damper = std::get_if<Damper>(&effect)) {
    *kind = LabBaselineKind::damper;
    c.damping_N_s_per_m = damper->damping_N_s_per_m;
  } else if (const auto* texture = std::get_if<Texture>(&effect)) {
    *kind = LabBaselineKind::texture;
    c.damping_N_s_per_m = texture->damping_N_s_per_m;
    c.width_m = texture->width_m;
    c.spacing_m = texture->spacing_m;
    c.offset_m = texture->offset_m;
    c.mirror = texture->mirror;
  } else {
    return false;
  }
  return true;
}

}  // namespace hapscene
