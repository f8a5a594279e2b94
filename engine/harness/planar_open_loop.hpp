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
#include "engine/harness/script_budget.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// Forces at many points, as fresh instances give them.
struct PlanarOpenLoopScan {
  std::vector<Vec2> force_N;  // per point, what the effects ask for (may be non-finite)
  ScriptBehaviour behaviour;
};

class PlanarOpenLoop {
 public:
  explicit PlanarOpenLoop(const PlanarScene& scene, double t_s = 0.0);

  // What the effects ask for at (x, v): built-in effects (open loop), plus every script
  // from a fresh, reset instance (faults recorded, at order key `order_key`).
  Vec2 force_N(const Vec2& x_m, const Vec2& v_m_per_s, double order_key = 0.0);
  // force_N after the static safety rules (non-finite -> 0, workspace, clamp).
  Vec2 output_N(const Vec2& x_m, const Vec2& force_N) const;

  // force_N at every point (at v), as the 1-D OpenLoop::scan finds it: one instance
  // called over the points in order and another in reverse order, and fresh ones at a few
  // spread points; when all agree and nothing faulted those are the values, else every
  // point comes from fresh instances (charged to the budget), except for scripts that
  // keep state and restore it in reset(): one instance reset before each point, when
  // nothing faulted and it gives what fresh instances give at the spread points. Faults
  // are keyed by the point's index.
  PlanarOpenLoopScan scan(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s);

  // Records the faults fresh instances meet at every point at velocity v: one instance
  // over the points in order, and only when a script faults every point from a fresh one.
  void scan_faults(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s);

  bool has_scripts() const { return scene_.script_count > 0; }
  void set_time_s(double t_s) { t_s_ = t_s; }
  const ScriptFaultLog& faults() const { return faults_; }

 private:
  Vec2 fresh_force_N(const Vec2& x_m, const Vec2& v_m_per_s, double t_s, bool record, double order_key);
  ScriptList create_instances();
  std::vector<Vec2> sequential_N(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s, bool forward,
                                 std::vector<bool>* live);
  // One instance per script, reset() before the call at each point, in order.
  std::vector<Vec2> reset_each_N(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s, std::vector<bool>* live);

  const PlanarScene& scene_;
  double t_s_{};
  ScriptList none_;
  ScriptFaultLog faults_;
  ScriptCreationBudget budget_;
};

// "x 12.00 mm, y 130.00 mm, v (0, 0) m/s, t 0 s": a point, for messages.
std::string describe_planar_point(const Vec2& x_m, const Vec2& v_m_per_s, double t_s);

// The grid step of 2-D validate's open-loop scan for script faults (README "Validation
// in 2-D"), as test specs' region and fault scans use (kPlanarSpecGridStep_m).
inline constexpr double kPlanarFaultScanStep_m = 1e-3;

// The points of the scene's workspace box every `step_m` on both axes from its lower left
// corner (x outer, y inner), those inside the workspace (its polygon, when it has one).
std::vector<Vec2> planar_workspace_grid(const PlanarScene& scene, double step_m);

// The velocities of the 2-D scan for faults in motion: at rest, then each speed of
// kMotionScanVelocities_m_per_s along +x, -x, +y, -y.
std::vector<Vec2> planar_motion_scan_velocities();

// The script faults met in motion and over time (scan_faults over `x_m` at each velocity
// of planar_motion_scan_velocities() and each time of kMotionScanTimes_s, skipping what
// the scripts do not read, up to the first velocity and time that meet a fault), as
// scan_faults_in_motion does in 1-D. Empty for a scene without scripts.
ScriptFaultLog scan_planar_faults_in_motion(const PlanarScene& scene, const std::vector<Vec2>& x_m);

}  // namespace hapscene
