// The 2-DOF kinematics families: the Haplink's published check value, analytic Jacobians
// against central finite differences, the 2DIY's symmetry, out-of-reach poses and the
// condition number.
#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <utility>

#include "engine/devices/planar/linkage.hpp"

using namespace hapscene;

namespace {

// The course constants (REFERENCE-2D.md, "Haplink").
Linkage haplink_linkage() {
  Linkage linkage;
  linkage.family = LinkageFamily::serial_2r;
  linkage.serial.link_a_m = 0.087;
  linkage.serial.link_b_m = 0.100;
  linkage.serial.offset_a_rad = 0.8727;
  linkage.serial.offset_b_rad = -1.4;
  return linkage;
}

// The Haply 2DIY v3: proximal 70 mm, distal 90 mm, bases 38 mm apart.
Linkage haply_v3_linkage() {
  Linkage linkage;
  linkage.family = LinkageFamily::five_bar;
  linkage.five_bar.base_1_m = Vec2{{0.0, 0.0}};
  linkage.five_bar.base_2_m = Vec2{{0.038, 0.0}};
  linkage.five_bar.proximal_1_m = linkage.five_bar.proximal_2_m = 0.07;
  linkage.five_bar.distal_1_m = linkage.five_bar.distal_2_m = 0.09;
  return linkage;
}

// An asymmetric five-bar (unequal links, offset bases), so no term hides behind symmetry.
Linkage asymmetric_five_bar() {
  Linkage linkage;
  linkage.family = LinkageFamily::five_bar;
  linkage.five_bar.base_1_m = Vec2{{-0.01, 0.005}};
  linkage.five_bar.base_2_m = Vec2{{0.05, -0.002}};
  linkage.five_bar.proximal_1_m = 0.06;
  linkage.five_bar.proximal_2_m = 0.075;
  linkage.five_bar.distal_1_m = 0.095;
  linkage.five_bar.distal_2_m = 0.085;
  return linkage;
}

// Checks the analytic Jacobian against central differences at q; returns false when the
// pose is out of reach (nothing checked).
bool check_jacobian(const Linkage& linkage, const Vec2& q) {
  const LinkagePose pose = solve_linkage(linkage, q);
  if (!pose.valid) return false;
  const double step = 1e-6;
  for (int joint = 0; joint < 2; ++joint) {
    Vec2 ahead = q, behind = q;
    ahead[joint] += step;
    behind[joint] -= step;
    const LinkagePose a = solve_linkage(linkage, ahead);
    const LinkagePose b = solve_linkage(linkage, behind);
    if (!a.valid || !b.valid) return false;
    for (int axis = 0; axis < 2; ++axis) {
      const double numeric = (a.handle_m[axis] - b.handle_m[axis]) / (2.0 * step);
      CAPTURE(q[0]);
      CAPTURE(q[1]);
      CAPTURE(joint);
      CAPTURE(axis);
      CHECK(pose.jacobian.m[axis][joint] == doctest::Approx(numeric).epsilon(1e-6).scale(1e-3));
    }
  }
  return true;
}

}  // namespace

TEST_CASE("planar linkage: the Haplink tip at zero joint angles is the course's check value") {
  const LinkagePose pose = solve_linkage(haplink_linkage(), Vec2{{0.0, 0.0}});
  REQUIRE(pose.valid);
  CHECK(pose.handle_m[0] * 1e3 == doctest::Approx(-16.327652).epsilon(1e-7));
  CHECK(pose.handle_m[1] * 1e3 == doctest::Approx(142.337051).epsilon(1e-7));
  // The elbow is link a from the base.
  CHECK(norm(pose.elbow_1_m) == doctest::Approx(0.087).epsilon(1e-12));
  CHECK(norm(pose.handle_m - pose.elbow_1_m) == doctest::Approx(0.100).epsilon(1e-12));
}

TEST_CASE("planar linkage: the Haplink's Jacobian is the course's formula and matches finite differences") {
  const Linkage linkage = haplink_linkage();
  const LinkagePose pose = solve_linkage(linkage, Vec2{{0.0, 0.0}});
  const double a = 0.8727, ab = 0.8727 - 1.4;
  CHECK(pose.jacobian.m[0][0] == doctest::Approx(-0.1 * std::cos(ab) - 0.087 * std::cos(a)));
  CHECK(pose.jacobian.m[0][1] == doctest::Approx(-0.1 * std::cos(ab)));
  CHECK(pose.jacobian.m[1][0] == doctest::Approx(-0.1 * std::sin(ab) - 0.087 * std::sin(a)));
  CHECK(pose.jacobian.m[1][1] == doctest::Approx(-0.1 * std::sin(ab)));
  int checked = 0;
  for (double q1 = -1.5; q1 <= 1.5; q1 += 0.25) {
    for (double q2 = -2.5; q2 <= 2.5; q2 += 0.25) checked += check_jacobian(linkage, Vec2{{q1, q2}});
  }
  CHECK(checked == 13 * 21);
}

TEST_CASE("planar linkage: five-bar Jacobians match finite differences over a grid of poses") {
  for (const Linkage& linkage : {haply_v3_linkage(), asymmetric_five_bar()}) {
    for (int sign : {1, -1}) {
      Linkage mode = linkage;
      mode.five_bar.assembly_sign = sign;
      int checked = 0;
      for (double q1 = 0.3; q1 <= 3.0; q1 += 0.15) {
        for (double q2 = 0.1; q2 <= 2.8; q2 += 0.15) checked += check_jacobian(mode, Vec2{{q1, q2}});
      }
      // Most of the grid is reachable (the rest is refused, checked below).
      CHECK(checked > 150);
    }
  }
}

TEST_CASE("planar linkage: the 2DIY v3's handle is on the symmetry line when the joints mirror") {
  const Linkage linkage = haply_v3_linkage();
  const double d = 0.038;
  for (double t1_deg : {100.0, 120.0, 150.0, 168.0}) {
    CAPTURE(t1_deg);
    const double t1 = t1_deg * std::numbers::pi / 180.0;
    const LinkagePose pose = solve_linkage(linkage, Vec2{{t1, std::numbers::pi - t1}});
    REQUIRE(pose.valid);
    CHECK(pose.handle_m[0] == doctest::Approx(d / 2.0).epsilon(1e-12).scale(1e-9));
    CHECK(pose.handle_m[1] > 0.0);  // away from the base on the +1 assembly side
    CHECK(norm(pose.handle_m - pose.elbow_1_m) == doctest::Approx(0.09).epsilon(1e-12));
    CHECK(norm(pose.handle_m - pose.elbow_2_m) == doctest::Approx(0.09).epsilon(1e-12));
  }
  // The published reference pose (offsets 168 deg and 12 deg) is a mirror pose.
  const LinkagePose reference = solve_linkage(linkage, Vec2{{168.0 * std::numbers::pi / 180.0, 12.0 * std::numbers::pi / 180.0}});
  CHECK(reference.handle_m[0] == doctest::Approx(0.019).epsilon(1e-12));
}

TEST_CASE("planar linkage: poses out of reach are invalid, without NaN") {
  const Linkage linkage = haply_v3_linkage();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  // Elbows 195 mm apart, more than the distal links (95 + 85 mm) reach; elbows on top of
  // each other (equal bases and angles); non-finite angles.
  Linkage same_base = linkage;
  same_base.five_bar.base_2_m = Vec2{};
  // (The 2DIY v3 itself cannot stretch out of reach: its elbows are at most 178 mm apart,
  // less than its two 90 mm distal links; the asymmetric linkage can.)
  for (const auto& [geometry, q] : {std::pair{asymmetric_five_bar(), Vec2{{std::numbers::pi, 0.0}}},
                                     std::pair{same_base, Vec2{{1.0, 1.0}}},
                                     std::pair{linkage, Vec2{{nan, 0.0}}},
                                     std::pair{linkage, Vec2{{1.0, inf}}}}) {
    const LinkagePose pose = solve_linkage(geometry, q);
    CHECK_FALSE(pose.valid);
    CHECK(all_finite(pose.handle_m));
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) CHECK(std::isfinite(pose.jacobian.m[r][c]));
    }
  }
  // A serial arm with non-finite angles is refused too.
  CHECK_FALSE(solve_linkage(haplink_linkage(), Vec2{{nan, 0.0}}).valid);
}

TEST_CASE("planar linkage: condition number is 1 for an orthogonal J, infinite when singular") {
  Jacobian2 rotation;
  const double angle = 0.7;
  rotation.m[0][0] = std::cos(angle);
  rotation.m[0][1] = -std::sin(angle);
  rotation.m[1][0] = std::sin(angle);
  rotation.m[1][1] = std::cos(angle);
  CHECK(condition_number(rotation) == doctest::Approx(1.0).epsilon(1e-12));
  Jacobian2 scaled;
  scaled.m[0][0] = 3.0;
  scaled.m[1][1] = -0.5;
  CHECK(condition_number(scaled) == doctest::Approx(6.0).epsilon(1e-12));
  // The Haplink stretched straight (a + b aligned with a: q2 = -offset_b) is singular.
  // (Rounding of q2 + offset_b leaves it a hair off, so "infinite" is beyond 1e12.)
  const LinkagePose straight = solve_linkage(haplink_linkage(), Vec2{{0.2, 1.4}});
  CHECK(condition_number(straight.jacobian) > 1e12);
  CHECK(std::isinf(condition_number(Jacobian2{})));
  // Near it, large and finite.
  const LinkagePose near = solve_linkage(haplink_linkage(), Vec2{{0.2, 1.4 + 1e-4}});
  CHECK(condition_number(near.jacobian) > 1e3);
  CHECK(std::isfinite(condition_number(near.jacobian)));
}

TEST_CASE("planar linkage: tau = J^T F and the handle velocity J q_dot agree by virtual work") {
  const LinkagePose pose = solve_linkage(haply_v3_linkage(), Vec2{{2.0, 1.0}});
  REQUIRE(pose.valid);
  const Vec2 force{{1.5, -0.75}};
  const Vec2 q_dot{{0.3, -0.2}};
  CHECK(dot(force, handle_velocity_m_per_s(pose.jacobian, q_dot)) ==
        doctest::Approx(dot(joint_torques_N_m(pose.jacobian, force), q_dot)).epsilon(1e-12));
}
