#pragma once
// Helpers for the planar device tests: the shipped planar profiles and a small inverse
// kinematics (Newton steps on the forward kinematics) to reach task-space points.
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "engine/devices/planar/linkage.hpp"

namespace hapscene::test {

inline const std::array<std::string, 5>& shipped_planar_profiles() {
  static const std::array<std::string, 5> names{"haplink", "hapkit_pantograph", "haply2diy_v1", "haply2diy_v2",
                                                "haply2diy_v3"};
  return names;
}

// Joint angles that put the handle at `target_m`, from `start_rad` by damped Newton steps;
// nothing when the iteration leaves the linkage's reach or does not converge.
inline std::optional<Vec2> inverse_kinematics(const Linkage& linkage, const Vec2& target_m, Vec2 q) {
  for (int iteration = 0; iteration < 200; ++iteration) {
    const LinkagePose pose = solve_linkage(linkage, q);
    if (!pose.valid) return std::nullopt;
    const Vec2 error = target_m - pose.handle_m;
    if (norm(error) < 1e-12) return q;
    const Jacobian2& j = pose.jacobian;
    const double det = j.m[0][0] * j.m[1][1] - j.m[0][1] * j.m[1][0];
    if (det == 0.0) return std::nullopt;
    Vec2 step{{(j.m[1][1] * error[0] - j.m[0][1] * error[1]) / det,
               (-j.m[1][0] * error[0] + j.m[0][0] * error[1]) / det}};
    const double length = norm(step);
    if (length > 0.1) step *= 0.1 / length;
    q += step;
  }
  return std::nullopt;
}

}  // namespace hapscene::test
