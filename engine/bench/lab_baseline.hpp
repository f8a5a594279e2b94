#pragma once
// The baseline a Hapkit user has today: the lab's per-tick code written by hand, the way
// the reference sketch does it (flip counting on the raw reading, the linear counts fit,
// the 0.9 / 0.1 average of the new and previous velocity differences, one hard-coded force law, torque and duty). Compiled
// into the benchmark so `hapscene bench` can put the engine's cost next to it.
#include <cstdint>

#include "engine/scene/scene.hpp"

namespace hapscene {

// The hand-written program's constants, copied from a scene's profile and single effect.
struct LabBaselineConstants {
  double slope_deg_per_count{};
  double offset_deg{};
  std::int32_t flip_threshold_counts{};
  std::int32_t span_counts{};
  double handle_radius_m{};
  double pulley_radius_m{};
  double sector_radius_m{};
  double motor_constant_N_m{};
  double period_s{};
  // The one effect, as the lab code would hard-code it.
  double stiffness_N_per_m{};
  double position_m{};     // spring center or wall position
  bool solid_above{};
  double damping_N_s_per_m{};
  double width_m{};
  double spacing_m{};
  double offset_m{};
  bool mirror{};           // texture fields mirrored about offset_m
};

// What the sketch keeps between loop() calls.
struct LabBaselineState {
  std::int32_t last_raw{};
  std::int32_t flips{};
  bool started{};
  double last_x_m{};
  double last_dxh_m_per_s{};  // the previous raw difference
  double duty{};
  bool direction_high{};
  double velocity_m_per_s{};  // the sketch's filtered velocity (computed every loop)
};

enum class LabBaselineKind { spring, wall, damper, texture };

// The constants for `scene` when it is one lab effect; false when it is anything else.
bool lab_baseline_for(const Scene& scene, LabBaselineKind* kind, LabBaselineConstants* constants);

// One loop() of the hand-written sketch for each lab environment.
void lab_spring_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept;
void lab_wall_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept;
void lab_damper_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept;
void lab_texture_tick(const LabBaselineConstants& c, std::int32_t raw, LabBaselineState* s) noexcept;

// The floor: the same ticks folded by hand, as fast as plain C++ gets without changing
// the maths: counts to metres one multiply-add, no division (1 / period and the torque
// and motor constants folded at set-up), the velocity filter only where the force uses
// it, flip counting and the duty cap without branches. The bench calls them out of line,
// once per tick, as the engine's step() is.
struct LabFoldedConstants {
  double m_per_count{};
  double offset_m{};
  std::int32_t flip_threshold_counts{};
  std::int32_t span_counts{};
  double new_difference_per_m{};  // 0.9 / period
  double duty_squared_per_N{};    // duty^2 per newton: r_pulley / r_sector * r_handle / Km
  double stiffness_N_per_m{};
  double position_m{};
  bool solid_above{};
  double damping_N_s_per_m{};
  double width_m{};
  double period_m{};
  double per_period{};
  double texture_offset_m{};
  bool mirror{};
};
LabFoldedConstants fold_lab_constants(const LabBaselineConstants& c);
void lab_spring_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept;
void lab_wall_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept;
void lab_damper_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept;
void lab_texture_folded(const LabFoldedConstants& f, std::int32_t raw, LabBaselineState* s) noexcept;

}  // namespace hapscene
