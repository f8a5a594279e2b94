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

// The five-bar's solve (linkage.cpp): out of line, as it is long.
LinkagePose solve_five_bar(const FiveBarGeometry& g, const Vec2& q_rad) noexcept;

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
    *pose = solve_five_bar(linkage.five_bar, q_rad);
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

// The 2-norm condition number of J (largest over smallest singular value; infinity at a
// singular pose). Safety ramps force out past the profile's limit.
double condition_number(const Jacobian2& j) noexcept;

}  // namespace hapscene
