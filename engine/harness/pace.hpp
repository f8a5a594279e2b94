#pragma once
// Whether a scene's scripts can keep up with its loop. A script within its per-call
// budget can still take tens of milliseconds of CPU per force() call (under the CPU-time
// backstop, or with a raised budget); such a scene cannot render at its rate, and
// validating it would take hours in simulated time. The harness measures the CPU time of
// script calls over a window and stops with a failed "pace" check when the average is
// above the tick period: ordinary scripts take microseconds per call, so the verdict is
// the same on any machine for them.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "engine/harness/checks.hpp"
#include "engine/harness/scan_pace.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// CPU time of the calling thread, in s.
double thread_cpu_time_s() noexcept;

// Calls the scene's scripts (fresh instances, as a run's first ticks: reset, then one
// force() per tick period with x across the workspace) up to kPaceWindowCalls times,
// stopping as soon as their CPU time exceeds what the window allows at the tick period.
// Empty when the scene has no scripts or they keep up, else the failed "pace" check.
std::optional<CheckResult> check_script_pace(const Scene& scene);
// The same for a planar scene, x along the diagonal of its workspace box.
std::optional<CheckResult> check_script_pace(const PlanarScene& scene);

// The same during a closed-loop run, per window of kPaceWindowCalls ticks (the CPU time
// of whole ticks, which the scripts dominate when they are slow): tick() is called once
// per tick; it reads the clock every kPaceCheckEvery ticks and says from when on the
// run should stop. No allocation.
class PaceWatch {
 public:
  static constexpr std::uint64_t kPaceCheckEvery = 16;
  explicit PaceWatch(double period_s) : period_s_(period_s) {}

  // False once the ticks of the current window took more CPU time than the window allows,
  // or once a stop was requested (stop_request.hpp; too_slow() stays false then).
  bool tick() noexcept;
  bool too_slow() const noexcept { return too_slow_; }
  // The failed "pace" check (only when too_slow()).
  CheckResult check(const Scene& scene) const;

 private:
  double period_s_;
  std::uint64_t ticks_{};
  std::uint64_t window_ticks_{};
  double window_start_s_{-1.0};
  bool too_slow_{};
  double measured_s_{};          // CPU time of the window that was too slow
  std::uint64_t measured_ticks_{};
  std::uint64_t measured_from_tick_{};
};

// The failed "pace" check: `what` (force(), the run's ticks) took `cpu_s` over `count`
// units (`per`: call, tick) measured over `over` ("the first 5 calls").
template <int N>
CheckResult pace_failure(const SceneOf<N>& scene, const char* what, const char* per, double cpu_s, std::uint64_t count,
                         const std::string& over);

// An evaluation stopped because its scripts are too slow for the loop (check_script_pace)
// or for its checks' scans (ScanPace): the failed "pace" check, whose detail says so.
class ScriptsTooSlow : public std::runtime_error {
 public:
  explicit ScriptsTooSlow(CheckResult check) : std::runtime_error(check.detail), check_(std::move(check)) {}
  const CheckResult& check() const noexcept { return check_; }

 private:
  CheckResult check_;
};

}  // namespace hapscene
