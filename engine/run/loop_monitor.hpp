#pragma once
// The loop's timing as it runs, for a reader on another thread (the live view): the
// runner stores into relaxed atomics once per tick when RunOptions::monitor is set, and
// never waits. The reader takes the largest wake-up lateness and tick compute seen since
// its last take (take_*: an exchange with 0; a value stored between the reader's load and
// the loop's store may land in the next period, which a display tolerates).
#include <atomic>
#include <cstdint>

namespace hapscene {

// Why the loop stopped on overruns (or, where they only report, which limit was passed).
enum class OverrunFault : std::uint8_t {
  none,
  streak,  // overrun_fault_ticks deadline misses in a row, made by the loop's own work
  window,  // more than overrun_window_misses misses within overrun_window_deadlines
};

// How a run ended, for a reader after its last tick.
enum class RunEnd : std::uint8_t {
  running,         // not yet
  duration,        // ran its whole duration
  stop_requested,  // asked to stop (Ctrl-C, a signal)
  overrun_fault,   // stopped on overruns, zero force (overrun_kind() says which)
  device_lost,     // the device went away (the run's summary says why)
};

class LoopMonitor {
 public:
  // Loop thread.
  void note_wake_late(std::uint64_t late_ns) noexcept { raise(&wake_late_max_ns_, late_ns); }
  void note_compute(std::uint64_t compute_ns) noexcept { raise(&compute_max_ns_, compute_ns); }
  void note_misses(std::uint64_t total_misses, std::uint64_t total_warnings) noexcept {
    deadline_misses_.store(total_misses, std::memory_order_relaxed);
    overrun_warnings_.store(total_warnings, std::memory_order_relaxed);
  }

  // The first overrun limit passed, when, and whether it stopped the run.
  void note_overrun(OverrunFault kind, double t_s, bool stopped) noexcept {
    overrun_t_s_.store(t_s, std::memory_order_relaxed);
    overrun_stopped_.store(stopped, std::memory_order_relaxed);
    overrun_kind_.store(kind, std::memory_order_release);
  }
  // Before the observers' on_finish.
  void note_end(RunEnd end) noexcept { end_.store(end, std::memory_order_release); }

  // Any thread.
  OverrunFault overrun_kind() const noexcept { return overrun_kind_.load(std::memory_order_acquire); }
  double overrun_t_s() const noexcept { return overrun_t_s_.load(std::memory_order_relaxed); }
  bool overrun_stopped() const noexcept { return overrun_stopped_.load(std::memory_order_relaxed); }
  RunEnd end() const noexcept { return end_.load(std::memory_order_acquire); }
  std::uint64_t deadline_misses() const noexcept { return deadline_misses_.load(std::memory_order_relaxed); }
  std::uint64_t overrun_warnings() const noexcept { return overrun_warnings_.load(std::memory_order_relaxed); }
  // The reader (one thread): the largest value since its previous take.
  std::uint64_t take_wake_late_max_ns() noexcept { return wake_late_max_ns_.exchange(0, std::memory_order_relaxed); }
  std::uint64_t take_compute_max_ns() noexcept { return compute_max_ns_.exchange(0, std::memory_order_relaxed); }

 private:
  static void raise(std::atomic<std::uint64_t>* slot, std::uint64_t value) noexcept {
    if (value > slot->load(std::memory_order_relaxed)) slot->store(value, std::memory_order_relaxed);
  }

  std::atomic<std::uint64_t> deadline_misses_{0};
  std::atomic<std::uint64_t> overrun_warnings_{0};
  std::atomic<std::uint64_t> wake_late_max_ns_{0};
  std::atomic<std::uint64_t> compute_max_ns_{0};
  std::atomic<OverrunFault> overrun_kind_{OverrunFault::none};
  std::atomic<double> overrun_t_s_{0.0};
  std::atomic<bool> overrun_stopped_{false};
  std::atomic<RunEnd> end_{RunEnd::running};
};

}  // namespace hapscene
