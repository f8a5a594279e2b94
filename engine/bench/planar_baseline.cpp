#include "engine/bench/planar_baseline.hpp"

#include <cmath>
#include <variant>

#include "engine/effects/planar/planar_shapes.hpp"

namespace hapscene {
namespace {

// The box as the lab writes it: inside, push to the nearest side (ties: left, right,
// bottom, top); outside, no force.
inline void box_force(const PlanarBaselineConstants& c, double x, double y, double* fx, double* fy) noexcept {
  *fx = 0.0;
  *fy = 0.0;
  if (!(c.box_min_m[0] < x && x < c.box_max_m[0] && c.box_min_m[1] < y && y < c.box_max_m[1])) return;
  const double left = x - c.box_min_m[0];
  const double right = c.box_max_m[0] - x;
  const double bottom = y - c.box_min_m[1];
  const double top = c.box_max_m[1] - y;
  const double nearest = std::fmin(std::fmin(left, right), std::fmin(bottom, top));
  if (left == nearest) *fx = c.stiffness_N_per_m * (c.box_min_m[0] - x);
  else if (right == nearest) *fx = c.stiffness_N_per_m * (c.box_max_m[0] - x);
  else if (bottom == nearest) *fy = c.stiffness_N_per_m * (c.box_min_m[1] - y);
  else *fy = c.stiffness_N_per_m * (c.box_max_m[1] - y);
}

}  // namespace

void haplink_box_tick(const PlanarBaselineConstants& c, const PlanarReading& reading,
                      PlanarBaselineState* s) noexcept {
  // Encoder counts to joint angles; joint 2 is read relative to link a (the coupling).
  const double q1 = c.rad_per_count[0] * reading.counts[0] + c.offset_rad[0];
  const double q2 = c.rad_per_count[1] * reading.counts[1] + c.offset_rad[1] + c.coupling * q1;
  // Forward kinematics and the Jacobian of the 2-link arm.
  const double a = q1 + c.offset_a_rad;
  const double ab = a + q2 + c.offset_b_rad;
  const double sa = std::sin(a), ca = std::cos(a), sab = std::sin(ab), cab = std::cos(ab);
  const double x = c.base_x_m - c.link_a_m * sa - c.link_b_m * sab;
  const double y = c.base_y_m + c.link_a_m * ca + c.link_b_m * cab;
  double fx, fy;
  box_force(c, x, y, &fx, &fy);
  // J^T F, then each motor: the coupling's transpose, the ratio and direction, the duty.
  const double tau1 = (-c.link_a_m * ca - c.link_b_m * cab) * fx + (-c.link_a_m * sa - c.link_b_m * sab) * fy;
  const double tau2 = -c.link_b_m * cab * fx - c.link_b_m * sab * fy;
  const double t1 = c.motor_per_joint_torque[0] * (tau1 + c.coupling * tau2);
  const double t2 = c.motor_per_joint_torque[1] * tau2;
  s->x_m[0] = x;
  s->x_m[1] = y;
  s->force_N[0] = fx;
  s->force_N[1] = fy;
  s->torque_N_m[0] = t1;
  s->torque_N_m[1] = t2;
  s->duty[0] = std::fmin(std::fabs(t1) * c.duty_per_N_m[0], c.duty_max[0]);
  s->duty[1] = std::fmin(std::fabs(t2) * c.duty_per_N_m[1], c.duty_max[1]);
  s->direction_high[0] = t1 > 0.0;
  s->direction_high[1] = t2 > 0.0;
  s->valid = true;
}

void five_bar_box_tick(const PlanarBaselineConstants& c, const PlanarReading& reading,
                       PlanarBaselineState* s) noexcept {
  constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
  const double q1 = reading.angle_deg[0] * kRadPerDeg + c.offset_rad[0];
  const double q2 = reading.angle_deg[1] * kRadPerDeg + c.offset_rad[1];
  // The elbows, then the handle where the distal links' circles meet.
  const double s1 = std::sin(q1), c1 = std::cos(q1), s2 = std::sin(q2), c2 = std::cos(q2);
  const double e1x = c.base_1_m[0] + c.proximal_1_m * c1, e1y = c.base_1_m[1] + c.proximal_1_m * s1;
  const double e2x = c.base_2_m[0] + c.proximal_2_m * c2, e2y = c.base_2_m[1] + c.proximal_2_m * s2;
  const double hx = e2x - e1x, hy = e2y - e1y;
  const double d = std::sqrt(hx * hx + hy * hy);
  const double ux = hx / d, uy = hy / d;
  const double along = (d * d + c.distal_1_m * c.distal_1_m - c.distal_2_m * c.distal_2_m) / (2.0 * d);
  const double half_chord_sq = c.distal_1_m * c.distal_1_m - along * along;
  if (!(d > 0.0) || !(half_chord_sq > 0.0)) {
    *s = PlanarBaselineState{};
    return;
  }
  const double half_chord = c.assembly_sign * std::sqrt(half_chord_sq);
  const double x = e1x + along * ux - half_chord * uy;
  const double y = e1y + along * uy + half_chord * ux;
  double fx, fy;
  box_force(c, x, y, &fx, &fy);
  // The Jacobian from the closure constraints (the distal links r1, r2 and the elbows'
  // velocities), then J^T F.
  const double r1x = x - e1x, r1y = y - e1y, r2x = x - e2x, r2y = y - e2y;
  const double det = r1x * r2y - r1y * r2x;
  const double k1 = (r1x * -c.proximal_1_m * s1 + r1y * c.proximal_1_m * c1) / det;
  const double k2 = (r2x * -c.proximal_2_m * s2 + r2y * c.proximal_2_m * c2) / det;
  const double tau1 = (r2y * fx - r2x * fy) * k1;
  const double tau2 = (-r1y * fx + r1x * fy) * k2;
  double t1 = c.motor_per_joint_torque[0] * tau1;
  double t2 = c.motor_per_joint_torque[1] * tau2;
  // The board takes a torque per motor, clamped to what the motor gives.
  t1 = std::fmax(-c.torque_max_N_m[0], std::fmin(t1, c.torque_max_N_m[0]));
  t2 = std::fmax(-c.torque_max_N_m[1], std::fmin(t2, c.torque_max_N_m[1]));
  s->x_m[0] = x;
  s->x_m[1] = y;
  s->force_N[0] = fx;
  s->force_N[1] = fy;
  s->torque_N_m[0] = t1;
  s->torque_N_m[1] = t2;
  s->duty[0] = std::fabs(t1) / c.torque_max_N_m[0];
  s->duty[1] = std::fabs(t2) / c.torque_max_N_m[1];
  s->direction_high[0] = t1 > 0.0;
  s->direction_high[1] = t2 > 0.0;
  s->valid = true;
}

bool planar_baseline_for(const PlanarScene& scene, PlanarBaselineKind* kind, PlanarBaselineConstants* constants) {
  if (scene.effects.size() != 1) return false;
  const auto* box = std::get_if<PlanarBox>(&scene.effects[0]);
  if (box == nullptr || !box->solid_inside) return false;
  const PlanarModel& model = scene.device_model.model;
  PlanarBaselineConstants& c = *constants;
  c = PlanarBaselineConstants{};
  for (int i = 0; i < 2; ++i) {
    const PlanarJointModel& joint = model.joints[static_cast<std::size_t>(i)];
    c.rad_per_count[i] = joint.rad_per_count;
    c.offset_rad[i] = joint.offset_rad;
    c.motor_per_joint_torque[i] = joint.motor_per_joint_torque;
    c.duty_per_N_m[i] = joint.duty_per_N_m;
    c.duty_max[i] = joint.duty_max;
    c.torque_max_N_m[i] = joint.motor_torque_max_N_m;
    c.box_min_m[i] = box->min_m[i];
    c.box_max_m[i] = box->max_m[i];
  }
  c.coupling = model.coupling;
  c.stiffness_N_per_m = box->stiffness_N_per_m;
  const PlanarJointModel& j1 = model.joints[0];
  const PlanarJointModel& j2 = model.joints[1];
  if (model.linkage.family == LinkageFamily::serial_2r) {
    // The Haplink: encoders (no wrap) and the linear duty law.
    if (j1.reads_angle || j2.reads_angle || j1.unwraps || j2.unwraps) return false;
    if (j1.law != PlanarDriveLaw::linear || j2.law != PlanarDriveLaw::linear) return false;
    const SerialArmGeometry& g = model.linkage.serial;
    c.link_a_m = g.link_a_m;
    c.link_b_m = g.link_b_m;
    c.offset_a_rad = g.offset_a_rad;
    c.offset_b_rad = g.offset_b_rad;
    c.base_x_m = g.base_m[0];
    c.base_y_m = g.base_m[1];
    *kind = PlanarBaselineKind::haplink_box;
    return true;
  }
  // A five-bar whose board reports angles and takes torques (the 2DIY), no coupling.
  if (!j1.reads_angle || !j2.reads_angle || model.coupling != 0.0) return false;
  if (j1.law != PlanarDriveLaw::torque || j2.law != PlanarDriveLaw::torque) return false;
  const FiveBarGeometry& g = model.linkage.five_bar;
  for (int i = 0; i < 2; ++i) {
    c.base_1_m[i] = g.base_1_m[i];
    c.base_2_m[i] = g.base_2_m[i];
  }
  c.proximal_1_m = g.proximal_1_m;
  c.proximal_2_m = g.proximal_2_m;
  c.distal_1_m = g.distal_1_m;
  c.distal_2_m = g.distal_2_m;
  c.assembly_sign = g.assembly_sign >= 0 ? 1.0 : -1.0;
  *kind = PlanarBaselineKind::five_bar_box;
  return true;
}

}  // namespace hapscene
