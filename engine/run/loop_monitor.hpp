#pragma once
// The loop's timing as it runs, for a reader on another thread (the live view): the
// runner stores into relaxed atomics once per tick when RunOptions::monitor is set, and
// never waits. The reader takes the largest wake-up lateness and tick compute seen since
// its last take (take_*: an exchange with 0; a value stored between the reader's load and
// the loop's store may land in the next period, which a display tolerates).
#include <atomic>
#include <cstdint>

namespace hapscene {

class LoopMonitor {
 public:
  // Loop thread.
  void note_wake_late(std::uint64_t late_ns) noexcept { raise(&wake_late_max_ns_, late_ns); }
  void note_compute(std::uint64_t compute_ns) noexcept { raise(&compute_max_ns_, compute_ns); }
  void note_misses(std::uint64_t total_misses, std::uint64_t total_warnings) noexcept {
    deadline_misses_.store(total_misses, std::memory_order_relaxed);
    overrun_warnings_.store(total_warnings, std::memory_order_relaxed);
  }

  // Any thread.
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
};

}  // namespace hapscene
