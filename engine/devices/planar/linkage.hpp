#pragma once
// The kinematics families of 2-DOF devices: joint angles q (rad) to the handle position
// p (m, the device's task frame) and the Jacobian J = dp/dq, so that a force F on the
// handle needs joint torques tau = J^T F. A profile chooses the family and gives its
// geometry; a new kit of a known family is a profile file, not code.
//
//   serial_2r: the Haplink (a 2-link arm): elbow e = base + L_a (-sin a, cos a), tip
//     p = e + L_b (-sin(a + b), cos(a + b)), a = q1 + offset_a, b = q2 + offset_b.
//   five_bar: a pantograph (two Hapkits, the Haply 2DIY): two proximal links from two base
//     points, two distal links meeting at the handle; the handle is the circle-circle
//     intersection on the side the profile names (the assembly mode).
// Facts and check values: ../shared/REFERENCE-2D.md.
#include <cmath>
#include <cstdint>

#include "engine/base/axes.hpp"

namespace hapscene {

enum class LinkageFamily : std::uint8_t { serial_2r, five_bar };

struct SerialArmGeometry {
  Vec2 base_m{};
  double link_a_m{};        // shoulder to elbow
  double link_b_m{};        // elbow to handle
  double offset_a_rad{};    // added to joint 1 before the formulas (the course's DELTATHETA_A)
  double offset_b_rad{};    // added to joint 2 (DELTATHETA_B)
};

struct FiveBarGeometry {
  Vec2 base_1_m{};          // joint 1's axis
  Vec2 base_2_m{};          // joint 2's axis
  double proximal_1_m{};    // from joint 1 to elbow 1
  double proximal_2_m{};
  double distal_1_m{};      // from elbow 1 to the handle
  double distal_2_m{};
  // Which of the two intersections is the handle: +1 the one to the left of the line from
  // elbow 1 to elbow 2 (the 2DIY's, handle away from the base), -1 the other.
  int assembly_sign{1};
};

struct Linkage {
  LinkageFamily family{LinkageFamily::serial_2r};
  SerialArmGeometry serial;
  FiveBarGeometry five_bar;
};

// J as rows: J[row][column], row = task axis (x, y), column = joint (1, 2).
struct Jacobian2 {
  double m[2][2]{};
};

// Everything one solve gives: the handle, the elbows (for plots and the plant's link
// masses) and the Jacobian at q.
struct LinkagePose {
  bool valid{};             // false when the linkage cannot close at q (five-bar out of reach)
  Vec2 handle_m{};
  Vec2 elbow_1_m{};         // serial_2r: the elbow; five_bar: the end of proximal link 1
  Vec2 elbow_2_m{};         // five_bar: the end of proximal link 2 (serial_2r: the handle)
  Jacobian2 jacobian{};
};

// The five-bar's solve, written into `pose` (inline: the tick of a five-bar device runs it
// every tick). The handle is where the circles of the distal links (centred on the elbows)
// meet. Its Jacobian follows from differentiating the two closure constraints
// |p - e_i|^2 = L_i^2: (p - e_i) . (dp - de_i) = 0, so M dp = diag((p - e_i) . de_i/dq_i) dq
// with the rows of M the distal link vectors. M is singular exactly when the distal links
// are aligned (the workspace boundary), where the pose is answered invalid.
[[gnu::always_inline]] inline void solve_five_bar(const FiveBarGeometry& g, const Vec2& q_rad,
                                                  LinkagePose* pose) noexcept {
  const double sin_1 = std::sin(q_rad[0]), cos_1 = std::cos(q_rad[0]);
  const double sin_2 = std::sin(q_rad[1]), cos_2 = std::cos(q_rad[1]);
  // Component by component (as Vec2's operators compute).
  const double e1_x = g.base_1_m[0] + g.proximal_1_m * cos_1, e1_y = g.base_1_m[1] + g.proximal_1_m * sin_1;
  const double e2_x = g.base_2_m[0] + g.proximal_2_m * cos_2, e2_y = g.base_2_m[1] + g.proximal_2_m * sin_2;
  pose->valid = false;
  pose->handle_m = Vec2{};
  pose->jacobian = Jacobian2{};
  pose->elbow_1_m = Vec2{{e1_x, e1_y}};
  pose->elbow_2_m = Vec2{{e2_x, e2_y}};
  const double h_x = e2_x - e1_x, h_y = e2_y - e1_y;
  const double hm = std::sqrt(h_x * h_x + h_y * h_y);
  if (!(hm > 0.0) || !std::isfinite(hm)) return;
  const double u_x = h_x / hm, u_y = h_y / hm;
  // Distance from e1 along u to the chord, and the half chord.
  const double along = (hm * hm + g.distal_1_m * g.distal_1_m - g.distal_2_m * g.distal_2_m) / (2.0 * hm);
  const double half_chord_sq = g.distal_1_m * g.distal_1_m - along * along;
  if (!(half_chord_sq > 0.0)) return;  // the distal links cannot meet (or only straight)
  const double side = g.assembly_sign >= 0 ? 1.0 : -1.0;
  const double half_chord = side * std::sqrt(half_chord_sq);
  // p = e1 + along u + half_chord u_left, u_left = (-u_y, u_x).
  const double p_x = (e1_x + along * u_x) + half_chord * -u_y;
  const double p_y = (e1_y + along * u_y) + half_chord * u_x;

  const double r1_x = p_x - e1_x, r1_y = p_y - e1_y;  // distal link 1
  const double r2_x = p_x - e2_x, r2_y = p_y - e2_y;  // distal link 2
  const double det = r1_x * r2_y - r1_y * r2_x;
  if (det == 0.0) return;
  // The dot products r_i . de_i/dq_i, summed from 0.0 as dot() does (the sign of a zero).
  const double c1 = (0.0 + r1_x * (-g.proximal_1_m * sin_1)) + r1_y * (g.proximal_1_m * cos_1);
  const double c2 = (0.0 + r2_x * (-g.proximal_2_m * sin_2)) + r2_y * (g.proximal_2_m * cos_2);
  // M^-1 = [[r2y, -r1y], [-r2x, r1x]] / det; column j of J is M^-1 e_j c_j.
  const double j00 = r2_y * c1 / det, j10 = -r2_x * c1 / det;
  const double j01 = -r1_y * c2 / det, j11 = r1_x * c2 / det;
  if (!(std::isfinite(p_x) && std::isfinite(p_y) && std::isfinite(j00) && std::isfinite(j01) &&
        std::isfinite(j10) && std::isfinite(j11))) {
    return;
  }
  pose->valid = true;
  pose->handle_m = Vec2{{p_x, p_y}};
  pose->jacobian.m[0][0] = j00;
  pose->jacobian.m[1][0] = j10;
  pose->jacobian.m[0][1] = j01;
  pose->jacobian.m[1][1] = j11;
}
// The same, returned (for tests and tools).
inline LinkagePose solve_five_bar(const FiveBarGeometry& g, const Vec2& q_rad) noexcept {
  LinkagePose pose;
  solve_five_bar(g, q_rad, &pose);
  return pose;
}

// The serial arm's solve, inline: the tick's sensor stage runs it every tick.
[[gnu::always_inline]] inline void solve_serial(const SerialArmGeometry& g, const Vec2& q_rad,
                                                LinkagePose* pose) noexcept {
  const double a = q_rad[0] + g.offset_a_rad;
  const double ab = a + q_rad[1] + g.offset_b_rad;
  const double sin_a = std::sin(a), cos_a = std::cos(a);
  const double sin_ab = std::sin(ab), cos_ab = std::cos(ab);
  pose->valid = true;
  // Component by component (as Vec2's + adds): GCC left the operator as a call here.
  const double elbow_x = g.base_m[0] + -g.link_a_m * sin_a;
  const double elbow_y = g.base_m[1] + g.link_a_m * cos_a;
  const double handle_x = elbow_x + -g.link_b_m * sin_ab;
  const double handle_y = elbow_y + g.link_b_m * cos_ab;
  pose->elbow_1_m = Vec2{{elbow_x, elbow_y}};
  pose->handle_m = Vec2{{handle_x, handle_y}};
  pose->elbow_2_m = pose->handle_m;
  // Columns: d p / d q1 moves both links, d p / d q2 only link b.
  pose->jacobian.m[0][0] = -g.link_a_m * cos_a - g.link_b_m * cos_ab;
  pose->jacobian.m[1][0] = -g.link_a_m * sin_a - g.link_b_m * sin_ab;
  pose->jacobian.m[0][1] = -g.link_b_m * cos_ab;
  pose->jacobian.m[1][1] = -g.link_b_m * sin_ab;
}

// Forward kinematics and the Jacobian at joint angles q (rad), written to `pose`. No
// allocation, no throw.
[[gnu::always_inline]] inline void solve_linkage(const Linkage& linkage, const Vec2& q_rad,
                                                 LinkagePose* pose) noexcept {
  if (!all_finite(q_rad)) {
    *pose = LinkagePose{};
  } else if (linkage.family == LinkageFamily::serial_2r) {
    solve_serial(linkage.serial, q_rad, pose);
  } else {
    solve_five_bar(linkage.five_bar, q_rad, pose);
  }
}
inline LinkagePose solve_linkage(const Linkage& linkage, const Vec2& q_rad) noexcept {
  LinkagePose pose;
  solve_linkage(linkage, q_rad, &pose);
  return pose;
}

// tau = J^T F.
inline Vec2 joint_torques_N_m(const Jacobian2& j, const Vec2& force_N) noexcept {
  return Vec2{{j.m[0][0] * force_N[0] + j.m[1][0] * force_N[1],
               j.m[0][1] * force_N[0] + j.m[1][1] * force_N[1]}};
}

// J q_dot: the handle velocity for joint velocities.
inline Vec2 handle_velocity_m_per_s(const Jacobian2& j, const Vec2& q_dot_rad_per_s) noexcept {
  return Vec2{{j.m[0][0] * q_dot_rad_per_s[0] + j.m[0][1] * q_dot_rad_per_s[1],
               j.m[1][0] * q_dot_rad_per_s[0] + j.m[1][1] * q_dot_rad_per_s[1]}};
}

// J^-T tau: the handle force joint torques make (solving J^T F = tau; zero at a singular
// pose).
inline Vec2 handle_force_from_joint_torques_N(const Jacobian2& j, const Vec2& joint_torque_N_m) noexcept {
  const double det = j.m[0][0] * j.m[1][1] - j.m[0][1] * j.m[1][0];
  if (!(std::fabs(det) > 1e-12)) return Vec2{};
  const Vec2& tau = joint_torque_N_m;
  // J^T = [[j00, j10], [j01, j11]].
  return Vec2{{(j.m[1][1] * tau[0] - j.m[1][0] * tau[1]) / det, (-j.m[0][1] * tau[0] + j.m[0][0] * tau[1]) / det}};
}

// The 2-norm condition number of J (largest over smallest singular value; infinity at a
// singular pose). Safety ramps force out past the profile's limit.
double condition_number(const Jacobian2& j) noexcept;

}  // namespace hapscene
