#pragma once
// The fixed-rate haptic loop. The same tick code runs in simulated time (as fast as
// possible, for tests and validation) and in real time (absolute deadlines: each tick's
// deadline is start + n * T, never "sleep one period"; a short spin before the deadline
// for precision; deadline misses and wake-up lateness counted).
//
// Each tick, in four named steps: read the device, step the scene, write the device,
// count. The observer (telemetry, live status, test traces) sees every tick and must not
// block.
#include <atomic>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "engine/base/latency_histogram.hpp"
#include "engine/devices/device.hpp"
#include "engine/run/hot_swap.hpp"
#include "engine/run/loop_clock.hpp"
#include "engine/run/loop_monitor.hpp"
#include "engine/run/tick_observer.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

enum class Pacing { simulated_time, real_time };

// What a real-time run does when its deadline misses pass the overrun limits below.
enum class OverrunResponse : std::uint8_t {
  by_device,  // stop where a late command can hurt (Device::deadlines_matter), report elsewhere
  stop,       // command zero force and end the run: a fault
  report,     // count and report the crossing; the run goes on
};

struct RunOptions {
  double duration_s{2.0};
  Pacing pacing{Pacing::real_time};
  // Set from another thread (e.g. on Ctrl-C) to end the run at the next tick.
  const std::atomic<bool>* stop_requested{nullptr};
  // Hot reload: scenes offered here replace the running one at a tick boundary (one
  // exchange per axis count, null for none; set_reload_exchange<N> and reload_exchange<N>
  // reach the run's).
  AxesTuple<SceneExchangePointer> reload{};
  // Sustained overruns: this many deadline misses in a row (a single stall of k periods
  // counts k) is a warning, this many a fault: the device is commanded zero force and
  // the run ends. The fault counts only the misses the loop's own work made (the tick, the
  // device's read and write, the observers took too long); misses after a late wake-up
  // (the OS or the VM did not run the loop in time: an isolated stall of the system) and
  // misses while a simulated device computed its period (Device::advance: a simulated
  // board's process that fell behind real time) are counted, warned of, and fault only as
  // frequent misses (the window below).
  std::uint32_t overrun_warn_ticks{3};
  std::uint32_t overrun_fault_ticks{10};
  // Frequent overruns: more than overrun_window_misses deadline misses among the last
  // overrun_window_deadlines deadlines (a sliding window; at most kMaxOverrunWindow) is a
  // fault too. Periodic slow ticks never make a streak of 10, yet leave the device
  // running at a fraction of its rate. 100 of 1000: a loaded machine without real-time
  // scheduling misses far fewer (docs/explanation/loop.md gives the measurement).
  std::uint32_t overrun_window_deadlines{1000};
  std::uint32_t overrun_window_misses{100};
  // The four numbers above are deadlines at 1 kHz. Above 1 kHz each is scaled by
  // rate / 1 kHz (overrun_limits_at), so they stand for the same time at any rate: a
  // stall of a few milliseconds, which a desktop or a VM has now and then, faults a
  // 10 kHz run no sooner than a 1 kHz one (10 ms without a command in a row, or over
  // 100 ms of misses within a second, still do). At 1 kHz and below they are unchanged.
  // What passing those limits does (by default: stop on a device with a motor, report on
  // a simulated one, whose world waits for the loop).
  OverrunResponse overruns{OverrunResponse::by_device};
  // When set, the loop's timing is published here as it runs (the live view reads it).
  LoopMonitor* monitor{nullptr};
  // The clock a real-time run keeps (null: the machine's monotonic clock).
  LoopClock* clock{nullptr};
};

// The overrun limits in force for a run at `rate_hz` (see RunOptions).
struct OverrunLimits {
  std::uint32_t warn_ticks{};
  std::uint32_t fault_ticks{};
  std::uint32_t window_deadlines{};
  std::uint32_t window_misses{};
};
OverrunLimits overrun_limits_at(const RunOptions& options, double rate_hz) noexcept;

// The exchange a run of a scene with N axes takes its reloads from (null: no reload).
template <int N>
SceneExchangeOf<N>* reload_exchange(const RunOptions& options) noexcept {
  return axes_get<N>(options.reload);
}

// Sets the exchange a run of a scene with N axes takes its reloads from.
template <int N>
void set_reload_exchange(RunOptions* options, SceneExchangeOf<N>* exchange) noexcept {
  axes_get<N>(options->reload) = exchange;
}

// The longest sliding window of deadlines the runner can judge (a fixed bit ring: no
// allocation in the loop).
inline constexpr std::uint32_t kMaxOverrunWindow = 16384;


// What happened to one script effect during a run.
struct ScriptReport {
  std::string name;            // "scripts/bumps.lua"
  bool disabled{};
  std::string fault;           // "scripts/bumps.lua:12: ..." when disabled
  double fault_time_s{};       // run time of the faulting call
  std::uint64_t skipped_calls{};  // ticks answered with 0 N after the fault
};

template <int N>
struct RunSummaryOf {
  std::string scene_name;         // the scene running at the end (after any reloads)
  std::uint64_t ticks{};
  double device_time_s{};         // ticks * period
  double wall_time_s{};           // elapsed real time
  double achieved_rate_hz{};      // real time: tick intervals per second between the first and last tick; simulated: the scene rate
  double max_abs_requested_N{};   // largest |force| (magnitude) the scene asked for
  double max_abs_output_N{};      // largest |force| commanded after safety
  SafetyCounters safety;
  std::uint64_t script_errors{};          // scripts disabled by an error or a bad return value
  std::uint64_t script_budget_overruns{}; // scripts disabled by their instruction, time or memory limit
  std::uint64_t deadline_misses{};  // deadlines passed without a command (a tick overrunning k periods: k)
  std::uint64_t stall_misses{};     // of these, the ones a late wake-up made (the system stalled the loop)
  std::uint64_t simulation_misses{};  // and the ones a simulated device's advance() made (its plant slower than real time)
  LatencyHistogram compute_ns;      // read + step + write of each tick
  LatencyHistogram wake_late_ns;    // real time: how late each tick started
  std::vector<ScriptReport> scripts;  // one per script effect, in scene order
  std::string realtime_note;        // real time: the scheduling obtained, or why not
  std::string realtime_hint;        // real time, when refused: how to allow it and what it costs not to
  std::uint32_t longest_miss_streak{};  // most deadline misses in a row
  std::uint64_t overrun_warnings{};     // times a streak reached overrun_warn_ticks
  double first_overrun_warning_s{-1.0}; // device time of the first warning (-1: none)
  bool overruns_stop{};                 // passing the limits stops the run (RunOptions::overruns, resolved)
  bool overrun_fault{};                 // the run ended on sustained or frequent overruns
  OverrunFault overrun_fault_kind{OverrunFault::none};  // which criterion was passed first (ended the run, when overruns_stop)
  double overrun_fault_s{};             // device time it was passed
  std::uint32_t most_misses_in_window{};  // most misses within any overrun window seen
  OverrunLimits overrun_limits;           // the limits in force (RunOptions scaled to the rate)
  bool device_lost{};                   // the run ended because the device was lost (Device::lost)
  // The safety limits at the start and at the end of the run (a hot reload may tighten
  // them, never loosen them): what the summary reports as in force.
  SafetyConfigOf<N> limits_at_start;
  SafetyConfigOf<N> limits_at_end;
};

using RunSummary = RunSummaryOf<1>;

// Runs `scene` on `device` for options.duration_s of device time, then commands zero
// force. (N comes from the scene; a device or observer of another N does not convert.)
template <int N>
RunSummaryOf<N> run_scene(const SceneOf<N>& scene, std::type_identity_t<DeviceOf<N>>& device,
                          const RunOptions& options, std::type_identity_t<TickObserverOf<N>>* observer);

}  // namespace hapscene
