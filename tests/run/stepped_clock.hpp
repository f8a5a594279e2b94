#pragma once
// A LoopClock that moves only when told (RunOptions::clock): sleeping and spinning jump to
// the time asked for, a tick takes no time unless a test passes some (SlowDevice), and a
// wake-up can be made late on purpose (a stall of the system). Real-time runs on it give
// the same misses, warnings and faults on any machine, however loaded.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <utility>

#include "engine/run/loop_clock.hpp"

namespace hapscene::test {

class SteppedClock final : public LoopClock {
 public:
  std::int64_t now_ns() noexcept override { return now_ns_; }
  void sleep_until(std::int64_t time_ns) noexcept override {
    now_ns_ = std::max(now_ns_, time_ns);
    ++wake_ups_;
    if (wake_late_) now_ns_ += wake_late_(wake_ups_);
  }
  void spin_until(std::int64_t time_ns) noexcept override { now_ns_ = std::max(now_ns_, time_ns); }

  // Time the loop's own work takes (called from a device's read or advance).
  void pass(std::int64_t duration_ns) noexcept { now_ns_ += duration_ns; }
  // How late the n-th wake-up (from 1) comes: the system did not run the loop in time.
  void make_wake_ups_late(std::function<std::int64_t(std::uint64_t)> late_ns) { wake_late_ = std::move(late_ns); }

 private:
  std::int64_t now_ns_{1'000'000'000};
  std::uint64_t wake_ups_{};
  std::function<std::int64_t(std::uint64_t)> wake_late_;
};

}  // namespace hapscene::test
