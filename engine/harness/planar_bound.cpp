#include "engine/harness/planar_bound.hpp"

#include <cmath>
#include <tuple>
#include <numbers>

#include "engine/base/errors.hpp"
#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/planar/simulated_planar.hpp"

namespace hapscene {
namespace {

// The bound at one pose; false when the pose is singular.
bool bound_at(const PlanarScene& scene, const Vec2& q_rad, PlanarPoseBound* out) {
  const LinkagePose pose = solve_linkage(scene.device.linkage, q_rad);
  if (!pose.valid) return false;
  const Jacobian2& j = pose.jacobian;
  out->condition = condition_number(j);
  const double det = j.m[0][0] * j.m[1][1] - j.m[0][1] * j.m[1][0];
  if (!(std::fabs(det) > 1e-12)) return false;
  // J^-1 (rows: joints; columns: task axes).
  const double inv[2][2] = {{j.m[1][1] / det, -j.m[0][1] / det}, {-j.m[1][0] / det, j.m[0][0] / det}};
  const Vec2 b = scene.device.plant.viscous_N_m_s_per_rad;
  const Vec2 tau_c = scene.device.plant.coulomb_N_m;
  // B_x = J^-T diag(b) J^-1, and its smaller eigenvalue.
  double bx[2][2];
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 2; ++c) bx[r][c] = b[0] * inv[0][r] * inv[0][c] + b[1] * inv[1][r] * inv[1][c];
  }
  const double mean = 0.5 * (bx[0][0] + bx[1][1]);
  const double spread = std::hypot(0.5 * (bx[0][0] - bx[1][1]), bx[0][1]);
  out->viscous_N_per_m = 2.0 * (mean - spread) / scene.period_s;
  // One count at the handle, and the weakest direction's friction.
  const PlanarModel& model = scene.device_model.model;
  double count_m = 0.0;
  for (int i = 0; i < 2; ++i) {
    count_m = std::fmax(count_m, std::hypot(j.m[0][i], j.m[1][i]) * planar_joint_resolution_rad(model, i));
  }
  double weakest_N = INFINITY;
  for (int k = 0; k < 72; ++k) {
    const double angle = k * std::numbers::pi / 72.0;
    const Vec2 u{{std::cos(angle), std::sin(angle)}};
    const double w0 = inv[0][0] * u[0] + inv[0][1] * u[1];
    const double w1 = inv[1][0] * u[0] + inv[1][1] * u[1];
    weakest_N = std::fmin(weakest_N, tau_c[0] * std::fabs(w0) + tau_c[1] * std::fabs(w1));
  }
  out->coulomb_N_per_m = count_m > 0.0 ? 2.0 * weakest_N / count_m : INFINITY;
  out->x_m = pose.handle_m;
  if (out->coulomb_N_per_m < out->viscous_N_per_m) {
    out->bound_N_per_m = out->coulomb_N_per_m;
    out->name = "2fc/D";
  } else {
    out->bound_N_per_m = out->viscous_N_per_m;
    out->name = "2b/T";
  }
  return true;
}

enum class PoseJudged { none, held, bounded };

// The bound with the handle at p: none (outside, unreachable, singular), held (past the
// condition limit: left out and counted), or bounded.
PoseJudged pose_bound_at(const PlanarScene& scene, const Vec2& p, PlanarPoseBound* pose) {
  if (!within_workspace(scene.safety, p)) return PoseJudged::none;
  Vec2 q{};
  try {
    q = planar_joint_angles_at(scene.device, p);
  } catch (const InputError&) {
    return PoseJudged::none;  // out of the linkage's reach
  }
  if (!bound_at(scene, q, pose)) return PoseJudged::none;
  if (norm(pose->x_m - p) > 1e-6) return PoseJudged::none;  // the nearest reachable pose, not this one
  // Past the condition limit the safety stage ramps force out: no wall is rendered there.
  if (!(pose->condition <= scene.device_model.condition_limit)) return PoseJudged::held;
  return PoseJudged::bounded;
}

// The largest stiffness among `group`'s effects, when their type's declared gain is a
// stiffness (engine/effects/effect_keys.hpp), into *stiffest.
template <typename T>
void stiffest_of(const std::vector<T>& group, double* stiffest) {
  static constexpr auto keys = T::keys();
  for (const KeyOf<T>& key : keys) {
    if (!key.key.gain || key.key.quantity != Quantity::stiffness_N_per_m) continue;
    for (const T& e : group) *stiffest = std::fmax(*stiffest, *read_numbers(key, e));
  }
}

}  // namespace

bool planar_pose_bound_at(const PlanarScene& scene, const Vec2& p_m, PlanarPoseBound* out) {
  PlanarPoseBound pose;
  if (pose_bound_at(scene, p_m, &pose) != PoseJudged::bounded) return false;
  *out = pose;
  return true;
}

PlanarStiffnessBound planar_stiffness_bound(const PlanarScene& scene, int grid) {
  PlanarStiffnessBound result;
  result.grid = grid;
  const Vec2 low = scene.safety.workspace_min_m;
  const Vec2 high = scene.safety.workspace_max_m;
  for (int row = 0; row < grid; ++row) {
    for (int column = 0; column < grid; ++column) {
      const Vec2 p{{low[0] + (high[0] - low[0]) * column / (grid - 1), low[1] + (high[1] - low[1]) * row / (grid - 1)}};
      PlanarPoseBound pose;
      const PoseJudged judged = pose_bound_at(scene, p, &pose);
      if (judged == PoseJudged::held) ++result.held_poses;
      if (judged != PoseJudged::bounded) continue;
      if (result.poses.empty() || pose.bound_N_per_m < result.lowest.bound_N_per_m) result.lowest = pose;
      if (result.poses.empty() || pose.bound_N_per_m > result.highest.bound_N_per_m) result.highest = pose;
      result.poses.push_back(pose);
    }
  }
  // The stiffest built-in effect: every type whose declared gain is a stiffness.
  std::apply([&](const auto&... groups) { (stiffest_of(groups, &result.stiffest_N_per_m), ...); }, scene.bank.groups);
  return result;
}

}  // namespace hapscene
