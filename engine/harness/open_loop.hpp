#pragma once
// Open-loop evaluation of a scene, as `probe`, test specs' `forces`/`zero_outside` and
// the harness's force-field scan use it. What a point means for a script that keeps
// state or reads time: every point is computed from fresh, reset script instances at
// one run time t (default 0), so the result never depends on which points were asked
// before or in what order. A script that faults is recorded (each message once, with the
// first point that raised it), never hidden behind the 0 N that a disabled script gives.
//
// Fresh instances re-run each script's top-level code, so an evaluation costs about
// (instances x creation time). That is bounded: an OpenLoop spends at most
// kOpenLoopCreateBudget_s of CPU time creating instances (plus at most one creation).
// Each creation is timed; an evaluation that would need more (many points of a script
// that keeps state or faults, or any scan of a script whose top level takes seconds) is
// refused before the work starts, with an InputError (exit 2) naming the scripts, their
// creation time and the number of points.
//
// The scripts' calls are bounded too (ScanPace): when they take more than a tenth of the
// tick period each on average (kScanPaceShare), the evaluation ends with ScriptsTooSlow,
// the failed "pace" check naming the scripts, after about one window of calls. It ends
// with CheckInterrupted when its thread was asked to stop (stop_request.hpp).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "engine/harness/scan_pace.hpp"
#include "engine/harness/script_budget.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

// Script faults seen while evaluating a scene: each distinct message once, in the order
// of their keys ("scripts/x.lua:3: attempt to ... (first at x 12.00 mm, v 0 m/s, t 0 s)").
// Of the places one message was seen, the one with the lowest order key (the position,
// in an open-loop scan; the time, in a run) is kept.
class ScriptFaultLog {
 public:
  // Records the faults of `scripts` (disabled instances), with where they were seen.
  void collect(const ScriptList& scripts, const std::string& where, double order_key = 0.0);
  // Records one message with where it was seen (empty: nowhere in particular).
  void add(const std::string& message, const std::string& where, double order_key = 0.0);
  void merge(const ScriptFaultLog& other);
  // At most kMaxMessages distinct messages are kept (a script whose message changes with
  // every call would otherwise flood the output and make each record cost a search).
  static constexpr std::size_t kMaxMessages = 20;

  const std::vector<std::string>& lines() const { return lines_; }
  // What a command prints of them, one line each: lines(), then, when some were omitted,
  // "... and script faults with other messages (only the 20 first `among` are shown)"
  // (`among`: "in the workspace", "in the grid", or empty).
  std::vector<std::string> report_lines(std::string_view among = {}) const;
  const std::vector<std::string>& messages() const { return messages_; }
  bool empty() const { return lines_.empty(); }

 private:
  void insert(const std::string& message, const std::string& line, double order_key);
  void sort_by_key();

  std::vector<std::string> messages_;  // the bare messages, for deduplication
  std::vector<std::string> lines_;     // message plus where
  std::vector<double> keys_;
  bool omitted_{};  // a message was left out because kMaxMessages others were kept (not
                    // how many times: that would depend on the order of the calls)
};

// What the script effects of a scene do beyond a fixed function of (x, v).
struct ScriptBehaviour {
  bool stateful{};      // a call's force depends on earlier calls (a virtual mass, a ball)
  bool time_varying{};  // the force depends on the run time s.t (a vibration)
  std::string note;     // which script and what, for reports ("" when neither)
  bool static_field() const { return !stateful && !time_varying; }
};

// Forces at many points, as fresh instances give them.
template <int N>
struct OpenLoopScanOf {
  std::vector<Axes<N>> force_N;  // per point, what the effects ask for (may be non-finite)
  // Per point, whether a script faulted there (its force then counts as 0 N: not what the
  // script meant). Empty when none did.
  std::vector<bool> script_faulted;
  ScriptBehaviour behaviour;
};
using OpenLoopScan = OpenLoopScanOf<1>;

// The order key of point `index` of a list of points, for the fault log: in 1-D the
// position (the lowest point that met a fault is kept), in 2-D the index (the first point
// in the order given).
inline double point_order_key(double x_m, std::size_t) { return x_m; }
inline double point_order_key(const Vec2&, std::size_t index) { return static_cast<double>(index); }

// The open loop of a scene with N axes (OpenLoop in 1-D, PlanarOpenLoop in 2-D: a point is
// a position in m, or [x, y]).
template <int N>
class OpenLoopOf {
 public:
  // `t_s`: the run time every point is evaluated at (s.t of scripts that read time).
  explicit OpenLoopOf(const SceneOf<N>& scene, double t_s = 0.0);

  // What the effects ask for at (x, v): built-in effects (open loop), plus every script
  // from a fresh, reset instance (faults recorded in faults()).
  Axes<N> force_N(const Axes<N>& x_m, const Axes<N>& v_m_per_s);
  // force_N after the static safety rules (non-finite -> 0, workspace, clamp).
  Axes<N> output_N(const Axes<N>& x_m, const Axes<N>& force_N) const;

  // force_N at every point (at v), and whether the scripts behave like a fixed field.
  // Fresh instances per point cost about 0.3 ms each, so the scan first calls one
  // instance over the points in order and another in reverse order, and fresh ones at up
  // to 9 spread points: when all agree and nothing faulted, those values are what fresh
  // instances give. Otherwise, for scripts that keep state and restore it in reset(), one
  // instance reset before each point, when nothing faulted and it gives what fresh
  // instances give at the spread points; else (state, or a fault) every point is computed
  // from fresh instances, unless `values_if_not_static` is false and the scripts keep
  // state (then force_N is empty). Time: fresh instances at several other run times, at
  // the spread points. Faults are keyed by point_order_key.
  OpenLoopScanOf<N> scan(const std::vector<Axes<N>>& x_m, const Axes<N>& v_m_per_s, bool values_if_not_static = true);

  // Records (in faults()) the script faults fresh instances meet at every point at
  // velocity v: one instance is called over the points in order, and only when a script
  // faults there is every point computed from a fresh instance, so that a fault is
  // reported only where a fresh run's first tick meets it. Cheap for a script that does
  // not fault (one call per point).
  void scan_faults(const std::vector<Axes<N>>& x_m, const Axes<N>& v_m_per_s);

  bool has_scripts() const { return scene_.script_count > 0; }
  // The run time later points are evaluated at (the creation budget stays charged).
  void set_time_s(double t_s) { t_s_ = t_s; }
  const ScriptFaultLog& faults() const { return faults_; }

 private:
  // (`faulted`, when given: whether a script faulted at this point.)
  Axes<N> fresh_force_N(const Axes<N>& x_m, const Axes<N>& v_m_per_s, double t_s, bool record, double order_key,
                        bool* faulted = nullptr);
  // New, reset instances of the scene's scripts, charged to the creation budget (throws
  // InputError before a creation that would exceed it).
  ScriptList create_instances();
  // One instance per script called at the points in order (or in reverse); `live[i]` is
  // false where a script had faulted before or at that call.
  std::vector<Axes<N>> sequential_N(const std::vector<Axes<N>>& x_m, const Axes<N>& v_m_per_s, bool forward,
                                    std::vector<bool>* live);

  const SceneOf<N>& scene_;
  double t_s_{};
  ScriptList none_;
  ScriptFaultLog faults_;
  ScriptCreationBudget budget_;
  ScanPace pace_;
};
using OpenLoop = OpenLoopOf<1>;

// One instance per script in `scripts`, reset() before the call at each point of `x_m` in
// order (at velocity v, run time t): what fresh instances give when the scripts' reset()
// restores all their state, at two calls a point instead of a creation. `live[i]` is
// false where a script had faulted at or before point i. The calls are charged to `pace`
// (ScriptsTooSlow, CheckInterrupted as for OpenLoopOf). (1-D and 2-D open loops.)
template <int N>
std::vector<Axes<N>> reset_each_point_N(const SceneOf<N>& scene, ScriptList& scripts, const std::vector<Axes<N>>& x_m,
                                        const Axes<N>& v_m_per_s, double t_s, ScanPace* pace, std::vector<bool>* live);

// The script faults met in motion and over time, which a scan at rest (v = 0, t = 0)
// misses: scan_faults over `x_m` at each of kMotionScanVelocities_m_per_s (both signs,
// up to the fastest the handle can move) and kMotionScanTimes_s, skipping velocities or
// times the scene's scripts do not read, in that order, up to the first velocity and time
// that meet a fault. Deterministic; empty for a scene without scripts. In 2-D the
// velocities are motion_scan_velocities<2>().
inline constexpr double kMotionScanVelocities_m_per_s[] = {0.0, 0.01, -0.01, 0.1, -0.1, 0.5, -0.5, 2.0, -2.0};
inline constexpr double kMotionScanTimes_s[] = {0.0, 0.5, 3.0};
template <int N>
ScriptFaultLog scan_faults_in_motion(const SceneOf<N>& scene, const std::vector<Axes<N>>& x_m);

// The velocities of the scan for faults in motion: kMotionScanVelocities_m_per_s in 1-D;
// in 2-D at rest, then each speed of it along +x, -x, +y, -y.
template <int N>
std::vector<Axes<N>> motion_scan_velocities();
template <>
std::vector<double> motion_scan_velocities<1>();
template <>
std::vector<Vec2> motion_scan_velocities<2>();

// "x 12.00 mm, v 0 m/s, t 0 s", "x 12.00 mm, y 130.00 mm, v (0, 0) m/s, t 0 s": a
// point, for messages.
std::string describe_point(double x_m, double v_m_per_s, double t_s);
std::string describe_point(const Vec2& x_m, const Vec2& v_m_per_s, double t_s);

}  // namespace hapscene
