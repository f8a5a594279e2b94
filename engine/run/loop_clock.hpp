#pragma once
// The time a real-time run keeps: what time it is, and waiting for a deadline. Runs use
// the machine's monotonic clock (monotonic_loop_clock()); a test hands the loop a clock it
// moves itself (tests/run/stepped_clock.hpp), so that a run's misses, warnings and faults
// are exact and repeat on any machine, however loaded.
#include <cstdint>

namespace hapscene {

class LoopClock {
 public:
  virtual ~LoopClock() = default;
  virtual std::int64_t now_ns() noexcept = 0;
  // Sleeps (gives the core away) until `time_ns`; may return a little late.
  virtual void sleep_until(std::int64_t time_ns) noexcept = 0;
  // Keeps the core until `time_ns`, for a wake-up on the dot.
  virtual void spin_until(std::int64_t time_ns) noexcept = 0;
};

// CLOCK_MONOTONIC: absolute sleeps (clock_nanosleep) and a busy spin.
LoopClock& monotonic_loop_clock() noexcept;

}  // namespace hapscene
