#include "engine/devices/planar/linkage.hpp"

#include <cmath>
#include <limits>

namespace hapscene {
// The handle is where the circles of the distal links (centred on the elbows) meet. Its
// Jacobian follows from differentiating the two closure constraints |p - e_i|^2 = L_i^2:
// (p - e_i) . (dp - de_i) = 0, so M dp = diag((p - e_i) . de_i/dq_i) dq with the rows of M
// the distal link vectors. M is singular exactly when the distal links are aligned (the
// workspace boundary), where the pose is answered invalid.
LinkagePose solve_five_bar(const FiveBarGeometry& g, const Vec2& q_rad) noexcept {
  LinkagePose pose;
  const double sin_1 = std::sin(q_rad[0]), cos_1 = std::cos(q_rad[0]);
  const double sin_2 = std::sin(q_rad[1]), cos_2 = std::cos(q_rad[1]);
  const Vec2 e1 = g.base_1_m + Vec2{{g.proximal_1_m * cos_1, g.proximal_1_m * sin_1}};
  const Vec2 e2 = g.base_2_m + Vec2{{g.proximal_2_m * cos_2, g.proximal_2_m * sin_2}};
  pose.elbow_1_m = e1;
  pose.elbow_2_m = e2;
  const Vec2 h = e2 - e1;
  const double hm = norm(h);
  if (!(hm > 0.0) || !std::isfinite(hm)) return pose;
  const Vec2 u = h / hm;
  const Vec2 u_left{{-u[1], u[0]}};
  // Distance from e1 along u to the chord, and the half chord.
  const double along = (hm * hm + g.distal_1_m * g.distal_1_m - g.distal_2_m * g.distal_2_m) / (2.0 * hm);
  const double half_chord_sq = g.distal_1_m * g.distal_1_m - along * along;
  if (!(half_chord_sq > 0.0)) return pose;  // the distal links cannot meet (or only straight)
  const double side = g.assembly_sign >= 0 ? 1.0 : -1.0;
  const Vec2 p = e1 + along * u + side * std::sqrt(half_chord_sq) * u_left;

  const Vec2 r1 = p - e1;  // distal link 1
  const Vec2 r2 = p - e2;  // distal link 2
  const double det = cross(r1, r2);
  if (det == 0.0) return pose;
  const Vec2 de1{{-g.proximal_1_m * sin_1, g.proximal_1_m * cos_1}};
  const Vec2 de2{{-g.proximal_2_m * sin_2, g.proximal_2_m * cos_2}};
  const double c1 = dot(r1, de1);
  const double c2 = dot(r2, de2);
  // M^-1 = [[r2y, -r1y], [-r2x, r1x]] / det; column j of J is M^-1 e_j c_j.
  pose.jacobian.m[0][0] = r2[1] * c1 / det;
  pose.jacobian.m[1][0] = -r2[0] * c1 / det;
  pose.jacobian.m[0][1] = -r1[1] * c2 / det;
  pose.jacobian.m[1][1] = r1[0] * c2 / det;
  pose.handle_m = p;
  pose.valid = all_finite(p) && std::isfinite(pose.jacobian.m[0][0]) && std::isfinite(pose.jacobian.m[0][1]) &&
               std::isfinite(pose.jacobian.m[1][0]) && std::isfinite(pose.jacobian.m[1][1]);
  if (!pose.valid) {
    pose.handle_m = Vec2{};
    pose.jacobian = Jacobian2{};
  }
  return pose;
}

// For a 2x2 matrix the singular values follow from the Frobenius norm and the determinant:
// s1^2 + s2^2 = |J|_F^2 and s1 s2 = |det J|, so s1 = (sqrt(F^2 + 2|det|) + sqrt(F^2 - 2|det|)) / 2
// and the condition number s1 / s2 = s1^2 / |det|.
double condition_number(const Jacobian2& j) noexcept {
  const double a = j.m[0][0], b = j.m[0][1], c = j.m[1][0], d = j.m[1][1];
  const double frobenius_sq = a * a + b * b + c * c + d * d;
  const double det = std::fabs(a * d - b * c);
  if (!std::isfinite(frobenius_sq) || !std::isfinite(det) || det == 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  const double sum = std::sqrt(frobenius_sq + 2.0 * det);
  const double difference = std::sqrt(std::fmax(frobenius_sq - 2.0 * det, 0.0));
  const double s1 = 0.5 * (sum + difference);
  return std::fmax(s1 * s1 / det, 1.0);
}

}  // namespace hapscene
