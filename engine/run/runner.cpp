#include "engine/run/runner.hpp"

#include <sys/prctl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <ctime>

#include "engine/run/loop_clock.hpp"
#include "engine/run/realtime.hpp"
#include "engine/run/warm_tick.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// What the safety stage does with the device's position this tick.
PositionHold position_hold(PositionStatus status) noexcept {
  switch (status) {
    case PositionStatus::fresh: return PositionHold::none;
    case PositionStatus::stale: return PositionHold::ramp_out;
    case PositionStatus::unmeasured:
    case PositionStatus::implausible: return PositionHold::cut;
  }
  return PositionHold::cut;
}

// Deadline misses among the last `size` deadlines: one bit per deadline in a fixed ring
// (1: missed), with a running count. Pushing costs a bit flip; nothing allocates.
class MissWindow {
 public:
  explicit MissWindow(std::uint32_t size) noexcept : size_(std::clamp<std::uint32_t>(size, 1, kMaxOverrunWindow)) {}

  // Records `count` deadlines, all met or all missed (only the last `size` matter).
  void push(std::uint64_t count, bool missed) noexcept {
    for (std::uint64_t i = 0; i < std::min<std::uint64_t>(count, size_); ++i) push_one(missed);
  }
  std::uint32_t misses() const noexcept { return misses_; }

 private:
  void push_one(bool missed) noexcept {
    std::uint64_t& word = bits_[next_ / 64];
    const std::uint64_t mask = std::uint64_t{1} << (next_ % 64);
    if ((word & mask) != 0) --misses_;  // the oldest deadline leaves the window
    if (missed) {
      word |= mask;
      ++misses_;
    } else {
      word &= ~mask;
    }
    next_ = next_ + 1 == size_ ? 0 : next_ + 1;
  }

  std::uint32_t size_;
  std::uint32_t next_{};
  std::uint32_t misses_{};
  std::array<std::uint64_t, kMaxOverrunWindow / 64> bits_{};
};

// A device's real-time stretch (Device::begin_real_time), ended however the run ends.
class RealTimeStretch {
 public:
  RealTimeStretch(DeviceStatus& device, bool real_time, double period_s) : device_(device), real_time_(real_time) {
    if (real_time_) device_.begin_real_time(period_s);
  }
  ~RealTimeStretch() {
    if (real_time_) device_.end_real_time();
  }
  RealTimeStretch(const RealTimeStretch&) = delete;
  RealTimeStretch& operator=(const RealTimeStretch&) = delete;

 private:
  DeviceStatus& device_;
  bool real_time_;
};

}  // namespace

OverrunLimits overrun_limits_at(const RunOptions& options, double rate_hz) noexcept {
  const double scale = std::max(1.0, rate_hz / 1000.0);
  const auto scaled = [scale](std::uint32_t deadlines) {
    return static_cast<std::uint32_t>(std::min(std::llround(deadlines * scale), static_cast<long long>(UINT32_MAX)));
  };
  return OverrunLimits{scaled(options.overrun_warn_ticks), scaled(options.overrun_fault_ticks),
                       std::min(scaled(options.overrun_window_deadlines), kMaxOverrunWindow),
                       scaled(options.overrun_window_misses)};
}

template <int N>
RunSummaryOf<N> run_scene(const SceneOf<N>& initial_scene, std::type_identity_t<DeviceOf<N>>& device,
                          const RunOptions& options, std::type_identity_t<TickObserverOf<N>>* observer) {
  RunSummaryOf<N> summary;
  TickStateOf<N> state = make_tick_state(initial_scene);
  HotSwapOf<N> hot_swap(initial_scene, reload_exchange<N>(options), &state, observer);
  // Rate and device stay for the whole run (a reload that changes them is refused).
  const SceneOf<N>& scene = initial_scene;
  const auto total_ticks = static_cast<std::uint64_t>(std::llround(options.duration_s * scene.rate_hz));
  const auto period_ns = static_cast<std::int64_t>(std::llround(scene.period_s * 1e9));
  const bool real_time = options.pacing == Pacing::real_time;
  LoopClock& clock = options.clock != nullptr ? *options.clock : monotonic_loop_clock();
  summary.overruns_stop = options.overruns == OverrunResponse::stop ||
                          (options.overruns == OverrunResponse::by_device && device.deadlines_matter());

  // Wake-ups exactly when asked: the default 50 us timer slack would eat the spin margin.
  // Real-time scheduling and locked memory when permitted, for the length of a real-time
  // run (see RealtimeGuard), for the loop and for the device's peers (a simulated board's
  // world, which keeps its own pace from here on).
  if (real_time) prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  const RealTimeStretch stretch(device, real_time, scene.period_s);
  const RealtimeGuard realtime(real_time, real_time ? device.realtime_peers() : std::vector<int>{});
  summary.realtime_note = realtime.note();
  summary.realtime_hint = realtime.hint();
  std::uint32_t miss_streak = 0;
  const OverrunLimits limits = overrun_limits_at(options, scene.rate_hz);
  summary.overrun_limits = limits;
  MissWindow miss_window(limits.window_deadlines);
  TickWarmerOf<N> warmer(initial_scene);  // the dry tick in the spin before each deadline

  if (observer != nullptr) observer->on_start(state);
  const std::int64_t start_ns = clock.now_ns();
  std::int64_t deadline_ns = start_ns;
  std::int64_t last_begin_ns = start_ns;  // start of the latest tick, for the loop rate
  std::int64_t woke_ns = start_ns;        // real time: when the loop woke for the latest tick
  std::uint32_t overrun_streak = 0;       // misses in a row the loop's own work made
  for (std::uint64_t tick = 0; tick < total_ticks; ++tick) {
    if (options.stop_requested != nullptr && options.stop_requested->load(std::memory_order_relaxed)) {
      break;
    }
    // Pace: wait for this tick's absolute deadline.
    if (real_time) {
      wait_until(clock, deadline_ns, [&] { warmer.warm(hot_swap.scene(), state); });
      woke_ns = clock.now_ns();
      const auto late_ns = static_cast<std::uint64_t>(woke_ns - deadline_ns);
      summary.wake_late_ns.record(late_ns);
      if (options.monitor != nullptr) options.monitor->note_wake_late(late_ns);
    }

    // Read the device, compute, write the device.
    const std::int64_t begin_ns = clock.now_ns();
    last_begin_ns = begin_ns;
    const CrossfadeOf<N>* fade = hot_swap.before_tick(&state);
    const typename DeviceOf<N>::Reading reading = device.read();
    if (device.take_restart()) restart_soft_start(&state.safety);  // the link came back
    state.safety.position_hold = position_hold(device.position_status());
    step(hot_swap.scene(), reading, &state, fade);
    device.write(state.command);
    const std::int64_t end_ns = clock.now_ns();
    warmer.note_reading(reading);  // what the next warm replays
    summary.compute_ns.record(static_cast<std::uint64_t>(end_ns - begin_ns));
    if (options.monitor != nullptr) options.monitor->note_compute(static_cast<std::uint64_t>(end_ns - begin_ns));
    collect_script_garbage(&state);  // in the slack, after the command is out

    // Count, and let device time pass.
    summary.max_abs_requested_N = std::fmax(summary.max_abs_requested_N, norm(state.effects_force_N));
    summary.max_abs_output_N = std::fmax(summary.max_abs_output_N, norm(state.output_N));
    if (observer != nullptr) observer->on_tick(state);
    // Device time passes. A simulated device computes it here (its plant, for the
    // period): the simulated world's time, which a real device spends in the world, not
    // the loop's own work. (A simulated board keeps its own pace in real time instead:
    // Device::begin_real_time.)
    const std::int64_t advance_begin_ns = real_time ? clock.now_ns() : 0;
    device.advance(scene.period_s);
    const std::int64_t advance_ns = real_time ? clock.now_ns() - advance_begin_ns : 0;
    if (device.lost()) {  // nothing left to drive: zero force below, and stop
      summary.device_lost = true;
      break;
    }

    deadline_ns += period_ns;
    if (real_time && clock.now_ns() > deadline_ns) {
      // Overran into the next tick: count every deadline passed without a command (a stall
      // of 50 periods is 50 misses, not one) and realign rather than burst to catch up.
      const std::int64_t now_ns = clock.now_ns();
      const std::int64_t behind_ns = now_ns - deadline_ns;
      const std::int64_t missed = behind_ns / period_ns + 1;
      summary.deadline_misses += static_cast<std::uint64_t>(missed);
      deadline_ns += missed * period_ns;
      // Of these, the misses the loop's own work made (the tick, the device's read and
      // write, the observers: those it would have made had it woken on time and the
      // device's simulation taken no time); then those the simulation's time added (a
      // simulated plant slower than real time); the rest came from a late wake-up, a stall of the
      // system (the OS or the VM did not run the loop), not of the loop.
      const auto misses_after = [&](std::int64_t late_by_ns) {
        return late_by_ns > 0 ? std::min(missed, late_by_ns / period_ns + 1) : std::int64_t{0};
      };
      const std::int64_t on_time_missed = misses_after(now_ns - woke_ns - period_ns);
      const std::int64_t own_missed = std::min(on_time_missed, misses_after(now_ns - woke_ns - advance_ns - period_ns));
      summary.simulation_misses += static_cast<std::uint64_t>(on_time_missed - own_missed);
      summary.stall_misses += static_cast<std::uint64_t>(missed - on_time_missed);
      overrun_streak = own_missed > 0
                           ? static_cast<std::uint32_t>(std::min<std::int64_t>(overrun_streak + own_missed, UINT32_MAX))
                           : 0;
      // Misses in a row of either kind warn; the loop's own fault to zero force and stop. An
      // isolated stall of the system is counted and warned of, and faults only as frequent
      // misses (the window below).
      const std::uint32_t streak_before = miss_streak;
      miss_streak = static_cast<std::uint32_t>(std::min<std::int64_t>(miss_streak + missed, UINT32_MAX));
      if (miss_streak > summary.longest_miss_streak) summary.longest_miss_streak = miss_streak;
      if (streak_before < limits.warn_ticks && miss_streak >= limits.warn_ticks) {
        ++summary.overrun_warnings;
        if (summary.first_overrun_warning_s < 0.0) summary.first_overrun_warning_s = state.t_s;
      }
      // Frequent overruns: too many misses within the sliding window of deadlines.
      miss_window.push(static_cast<std::uint64_t>(missed), /*missed=*/true);
      summary.most_misses_in_window = std::max(summary.most_misses_in_window, miss_window.misses());
      if (options.monitor != nullptr) options.monitor->note_misses(summary.deadline_misses, summary.overrun_warnings);
      // Past a limit: a fault (zero force, stop) or, where a late command hurts nothing,
      // the first crossing reported and the run going on.
      const bool streak_fault = overrun_streak >= limits.fault_ticks;
      if ((streak_fault || miss_window.misses() > limits.window_misses) &&
          summary.overrun_fault_kind == OverrunFault::none) {
        summary.overrun_fault_kind = streak_fault ? OverrunFault::streak : OverrunFault::window;
        summary.overrun_fault_s = state.t_s;
        if (options.monitor != nullptr) {
          options.monitor->note_overrun(summary.overrun_fault_kind, state.t_s, summary.overruns_stop);
        }
        if (summary.overruns_stop) {
          summary.overrun_fault = true;
          break;
        }
      }
    } else {
      miss_streak = 0;
      overrun_streak = 0;
      if (real_time) miss_window.push(1, /*missed=*/false);
    }
  }

  // The run is over (or faulted): the motor gets zero force.
  device.write(typename DeviceOf<N>::Command{});
  if (options.monitor != nullptr) {
    options.monitor->note_end(summary.overrun_fault   ? RunEnd::overrun_fault
                              : summary.device_lost   ? RunEnd::device_lost
                              : state.tick < total_ticks ? RunEnd::stop_requested
                                                         : RunEnd::duration);
  }

  if (observer != nullptr) observer->on_finish(state);

  // Script faults, reported once here: each disabled script says where and when.
  summary.scene_name = hot_swap.scene().name;
  std::size_t script_index = 0;
  for (const auto& effect : hot_swap.scene().effects) {
    if (const ScriptEffect* script = std::get_if<ScriptEffect>(&effect)) {
      const ScriptInstance& instance = *state.scripts[script_index++];
      summary.scripts.push_back(ScriptReport{script->program->display_name, instance.disabled(),
                                             std::string(instance.fault_message()),
                                             instance.fault_time_s(), instance.skipped_calls()});
      // Its fault, counted by kind: a limit overrun, or an error / bad return value.
      switch (instance.fault()) {
        case ScriptFault::none: break;
        case ScriptFault::error:
        case ScriptFault::bad_return: ++summary.script_errors; break;
        case ScriptFault::instruction_budget:
        case ScriptFault::time_limit:
        case ScriptFault::memory_limit: ++summary.script_budget_overruns; break;
      }
    }
  }
  summary.limits_at_start = initial_scene.safety;
  summary.limits_at_end = hot_swap.scene().safety;
  summary.ticks = state.tick;
  summary.safety = state.safety.counters;
  summary.device_time_s = static_cast<double>(state.tick) * scene.period_s;
  summary.wall_time_s = static_cast<double>(clock.now_ns() - start_ns) * 1e-9;
  // The rate the ticks achieved: intervals between the first and the last tick's start.
  const double ticks_span_s = static_cast<double>(last_begin_ns - start_ns) * 1e-9;
  summary.achieved_rate_hz = real_time && summary.ticks > 1 && ticks_span_s > 0.0
                                 ? static_cast<double>(summary.ticks - 1) / ticks_span_s
                                 : scene.rate_hz;
  return summary;
}

// The axis counts scenes are compiled for.
#define HAPSCENE_RUN_SCENE(N) \
  template RunSummaryOf<N> run_scene<N>(const SceneOf<N>&, DeviceOf<N>&, const RunOptions&, TickObserverOf<N>*);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_RUN_SCENE)
#undef HAPSCENE_RUN_SCENE

}  // namespace hapscene
