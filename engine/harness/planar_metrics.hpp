#pragma once
// What the harness measures in one 2-DOF validate run, from its tick records (after the
// run, outside the loop). The 1-D twin is metrics.hpp; the numbers mean the same with
// vectors: forces by their magnitude, slew and jitter on the change of the force vector.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/harness/metrics.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/run/runner.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

struct PlanarScriptPotential;  // planar_script_potential.hpp

// One tick of a 2-DOF validate run, with the simulator's truth beside what the host saw.
struct PlanarValidateRecord {
  double t_s{};
  Vec2 x_true_m{};         // the simulator's handle at the tick
  Vec2 x_m{};              // what the host measured
  Vec2 q_rad{};            // the simulator's joint angles at the tick
  Vec2 joint_torque_N_m{}; // the joint torques the command just written applies over the next tick
  Vec2 requested_N{};      // sum of the effects
  Vec2 output_N{};         // after safety
  Vec2 hand_N{};           // the hand's force on the handle
  double condition{};      // the sensed pose's Jacobian condition number
  bool pose_held{};        // the safety stage held force for the pose this tick (singular or invalid)
};

// Records every tick of a run into memory reserved up front, with each shape's proxy
// (ticks x shapes, planar_scenario_shapes' order; a declared shape has none and records
// the measured handle), and stops the run when its ticks take longer than the tick period
// (PaceWatch).
class PlanarValidateRecorder final : public TickObserverOf<2> {
 public:
  PlanarValidateRecorder(const SimulatedPlanar* device, std::size_t capacity, std::size_t shapes, double period_s,
                         std::atomic<bool>* stop);
  void on_tick(const TickStateOf<2>& s) noexcept override;

  std::vector<PlanarValidateRecord> records;
  std::vector<Vec2> proxies_m;   // records.size() x shapes
  std::size_t shapes{};
  PaceWatch pace;

 private:
  const SimulatedPlanar* device_;
  std::size_t capacity_;
  std::uint64_t pose_holds_seen_{};
  std::atomic<bool>* stop_;
};

struct PlanarScenarioMetrics {
  std::uint64_t ticks{};
  double duration_s{};
  double max_requested_N{};
  double max_output_N{};
  Vec2 max_output_x_m{};
  double max_output_t_s{};
  double time_at_limit_s{};
  double time_at_limit_fraction{};
  double max_slew_N_per_s{};     // largest |change of the output vector| per tick / T
  double force_jitter_N{};       // rms of |F[k] - (F[k-1] + F[k+1]) / 2|
  double jitter_peak_N{};
  Vec2 jitter_peak_x_m{};
  double jitter_peak_t_s{};
  // Passivity in 2-D: created = the work of the joint torques over the true joint motion
  // (sum of tau[k] . (q[k+1] - q[k]): F . dx at the handle) plus the change of the energy
  // the rendered springs store (each shape's spring to its proxy, a spring effect's to its
  // centre, each with the force limit's clamp; scripts store their field's potential,
  // planar_script_potential.hpp, when validate passes one; other effects store none);
  // dissipated = the joints' own viscous loss, sum of dq^T B dq / T over the ticks where
  // the motors pushed.
  PassivityMetrics passivity;
  // Oscillation in the watch window, along the motion's two principal axes: half-cycles
  // and frequency along the major axis, amplitudes the larger of the two.
  std::optional<OscillationMetrics> oscillation;
  Vec2 rest_m{};                 // mean position over the last 30 % of the watch window
  Vec2 major_axis{};             // the direction of largest motion in the window
  // Shapes.
  double max_penetration_m{};    // deepest true position into any shape's solid
  Vec2 max_penetration_x_m{};
  double max_penetration_t_s{};
  int max_penetration_shape{-1};
  std::uint64_t pop_throughs{};  // crossings of a solid the rendering did not hold back
  Vec2 first_pop_x_m{};
  double first_pop_t_s{-1.0};
  int first_pop_shape{-1};
  // Singularity.
  std::uint64_t pose_hold_ticks{};        // ticks the safety stage held force for the pose
  std::uint64_t pose_hold_force_ticks{};  // of those, ticks the effects asked for force
  double max_condition{};                 // the largest condition number sensed, where and when
  Vec2 max_condition_x_m{};
  double max_condition_t_s{};
  // Scripts and timing, as in 1-D.
  std::uint64_t script_errors{};
  std::uint64_t script_budget_overruns{};
  std::vector<ScenarioMetrics::ScriptFaultSeen> script_faults;
  double compute_p50_s{};
  double compute_p99_s{};
  double compute_max_s{};
  SafetyCounters safety;
};

// Measures one run; `final_q_rad` and `final_x_m` are the simulator's after the last tick.
// The springs' stored energy is taken at the measured handle (the stretch the rendering
// sees), the work at the true joint motion. `script_potential`: the scripts' stored
// energy (none credited when null).
PlanarScenarioMetrics measure_planar_run(const PlanarScene& scene, const std::vector<PlanarShapeGeometry>& shapes,
                                         const std::vector<PlanarValidateRecord>& records,
                                         const std::vector<Vec2>& proxies_m, const Vec2& final_q_rad,
                                         const Vec2& final_x_m, const RunSummaryOf<2>& summary,
                                         std::optional<double> watch_from_s,
                                         const PlanarScriptPotential* script_potential = nullptr);

// Counts the crossings of solids the rendering let through: the handle went into a
// shape's solid and, as it came out, the shape's proxy (the point its force pulls the
// handle toward) was across the solid from where it was when the handle went in (the
// solid's outward normals at the two faces more than 120 deg apart). A god-object proxy
// never crosses: a handle dragged through by the hand is pulled back toward the side it
// came in by, and is not counted. `proxies_m` is records.size() x shapes; for a shape
// rendered by its depth alone pass the handle's own positions (it then pops through
// whenever it crosses). A shape a script declares (`declared`: it has no proxy) is
// judged by the direction of the scene's requested force while the handle is in it: a
// crossing counts when the latest nonzero force points more than 120 deg from the first
// (the script pushed the handle out through the far side; a handle it never pushed, or
// always pushed the same way, is not counted). Fills pop_throughs and first_pop_*.
void count_pop_throughs(const std::vector<PlanarShapeGeometry>& shapes,
                        const std::vector<PlanarValidateRecord>& records, const std::vector<Vec2>& proxies_m,
                        PlanarScenarioMetrics* m);

}  // namespace hapscene
