#pragma once
// Open-loop evaluation of a planar (2-DOF) scene, as the 2-D `probe` and 2-D test specs
// use it: the 1-D OpenLoop's rules (engine/harness/open_loop.hpp) over points of the
// plane. Every point is computed as fresh, reset script instances give it at one run time
// t; each shape's proxy sits at the nearest point of its boundary (no history). Script
// faults are recorded once each, with the first point (in the order given) that met
// them. Fresh instances are charged to the same CPU-time budget as in 1-D
// (ScriptCreationBudget): an evaluation that would need more is refused before the work
// starts (InputError, exit 2, naming the scripts, their creation time and the points).
#include <string>
#include <vector>

#include "engine/harness/open_loop.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// The 1-D open loop's template with two axes (open_loop.hpp): force_N, output_N, scan and
// scan_faults over points of the plane, faults keyed by the point's index.
using PlanarOpenLoopScan = OpenLoopScanOf<2>;
using PlanarOpenLoop = OpenLoopOf<2>;

// The grid step of 2-D validate's open-loop scan for script faults (docs/reference/
// validate.md, "Validation in 2-D"), as test specs' region and fault scans use (kPlanarSpecGridStep_m).
inline constexpr double kPlanarFaultScanStep_m = 1e-3;

// The points of the scene's workspace box every `step_m` on both axes from its lower left
// corner (x outer, y inner), those inside the workspace (its polygon, when it has one).
std::vector<Vec2> planar_workspace_grid(const PlanarScene& scene, double step_m);

// The velocities of the 2-D scan for faults in motion: at rest, then each speed of
// kMotionScanVelocities_m_per_s along +x, -x, +y, -y.
inline std::vector<Vec2> planar_motion_scan_velocities() { return motion_scan_velocities<2>(); }

// The script faults met in motion and over time (scan_faults over `x_m` at each velocity
// of planar_motion_scan_velocities() and each time of kMotionScanTimes_s, skipping what
// the scripts do not read, up to the first velocity and time that meet a fault), as
// scan_faults_in_motion does in 1-D. Empty for a scene without scripts.
inline ScriptFaultLog scan_planar_faults_in_motion(const PlanarScene& scene, const std::vector<Vec2>& x_m) {
  return scan_faults_in_motion(scene, x_m);
}

}  // namespace hapscene
