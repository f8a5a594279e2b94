#pragma once
// The 2-D baseline: the course's inside-box written by hand, the way the lab code does it,
// for the Haplink (encoder counts to joint angles with the coupling, the serial arm's
// forward kinematics and Jacobian, the box, J^T F, each motor's torque to a duty by the
// linear law and a direction pin) and for the Haply 2DIY v3 (the board's angles, the
// five-bar's forward kinematics and Jacobian, the box, J^T F, a torque command clamped per
// motor). The box pushes to its nearest side, F = K (proxy - p), as the open-loop box of
// engine/effects/planar/planar_shapes.hpp does (the lab code has no proxy history).
// Compiled into the benchmark so `hapscene bench` can put the engine's 2-D tick next to it.
#include "engine/devices/planar/planar_model.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// The hand-written program's constants, copied from a scene's profile and its one box.
struct PlanarBaselineConstants {
  // Sensor: counts (or the board's degrees) to the joint angle, per joint.
  double rad_per_count[2]{};
  double offset_rad[2]{};
  double coupling{};          // q2 += coupling * q1 (the Haplink's cable)
  // Kinematics: serial arm
  double link_a_m{}, link_b_m{}, offset_a_rad{}, offset_b_rad{}, base_x_m{}, base_y_m{};
  // Kinematics: five-bar
  double base_1_m[2]{}, base_2_m[2]{};
  double proximal_1_m{}, proximal_2_m{}, distal_1_m{}, distal_2_m{};
  double assembly_sign{1.0};
  // Drive, per motor
  double motor_per_joint_torque[2]{};
  double duty_per_N_m[2]{};   // linear law
  double duty_max[2]{};
  double torque_max_N_m[2]{}; // torque law
  // The box
  double box_min_m[2]{}, box_max_m[2]{};
  double stiffness_N_per_m{};
};

// What the program keeps: the latest force and motor command (the outputs a test checks).
struct PlanarBaselineState {
  double x_m[2]{};
  double force_N[2]{};
  double torque_N_m[2]{};     // per motor, signed
  double duty[2]{};
  bool direction_high[2]{};
  bool valid{};               // five-bar: the linkage closed
};

enum class PlanarBaselineKind { haplink_box, five_bar_box };

// The constants for `scene` when it is one inside box on an encoder serial arm with the
// linear drive (the Haplink) or on an angle-reading five-bar with the torque drive (the
// 2DIY); false otherwise.
bool planar_baseline_for(const PlanarScene& scene, PlanarBaselineKind* kind, PlanarBaselineConstants* constants);

// One loop() of the hand-written program.
void haplink_box_tick(const PlanarBaselineConstants& c, const PlanarReading& reading,
                      PlanarBaselineState* s) noexcept;
void five_bar_box_tick(const PlanarBaselineConstants& c, const PlanarReading& reading,
                       PlanarBaselineState* s) noexcept;

}  // namespace hapscene
