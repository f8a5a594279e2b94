#pragma once
// The stiffness bound of a 2-DOF device per pose. The sampled-wall bounds of 1-D
// (validate.hpp's passivity_bound: 2 b / T, Colgate and Schenkel; 2 f_c / D, Abbott and
// Okamura) hold per direction with the device's own damping and friction in that
// direction, and on a linkage those change over the workspace. At each pose of a grid
// over the workspace (those the linkage reaches, inside the workspace):
//   viscous: the joints' viscous damping B (the profile's plant estimate, per joint) seen
//            at the handle, B_x = J^-T B J^-1; along a unit direction u the damping is
//            u^T B_x u, so the bound is 2 lambda_min(B_x) / T (its weakest direction);
//   coulomb: the joints' Coulomb torques seen at the handle moving along u,
//            f_c(u) = sum_i tau_c,i |(J^-1 u)_i|, against D, the task-space length of one
//            sensor count (the larger of the two joints' |J column| x resolution):
//            min over u of 2 f_c(u) / D (72 directions);
// and the pose's bound is the smaller of the two, named as in 1-D ("2b/T", "2fc/D").
// Poses past the profile's condition_limit are left out (the safety stage ramps force out
// there, so no wall is rendered) and counted.
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct PlanarPoseBound {
  Vec2 x_m{};
  double viscous_N_per_m{};   // 2 lambda_min(B_x) / T
  double coulomb_N_per_m{};   // min over directions of 2 f_c(u) / D
  double bound_N_per_m{};     // the smaller
  const char* name{"2b/T"};
  double condition{};         // the Jacobian's condition number there
};

struct PlanarStiffnessBound {
  int grid{};                          // points per side of the grid (grid x grid)
  std::vector<PlanarPoseBound> poses;  // the poses reached, row by row from the bottom left
  int held_poses{};                    // poses reached past the condition limit (left out: no force there)
  PlanarPoseBound lowest;              // the pose with the smallest bound
  PlanarPoseBound highest;             // and the largest
  double stiffest_N_per_m{};           // the scene's stiffest shape or spring (0: none)
};

// The bound over a grid x grid grid spanning the scene's workspace box.
PlanarStiffnessBound planar_stiffness_bound(const PlanarScene& scene, int grid = 11);

// The bound with the handle at p_m, judged as a grid point is: false when p_m is outside
// the workspace, out of the linkage's reach, singular or past the condition limit (no
// wall is rendered there).
bool planar_pose_bound_at(const PlanarScene& scene, const Vec2& p_m, PlanarPoseBound* out);

}  // namespace hapscene
