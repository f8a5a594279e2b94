#include "engine/run/loop_clock.hpp"

#include <time.h>

#include "engine/base/clock.hpp"

namespace hapscene {
namespace {

class MonotonicLoopClock final : public LoopClock {
 public:
  std::int64_t now_ns() noexcept override { return monotonic_now_ns(); }
  void sleep_until(std::int64_t time_ns) noexcept override {
    if (monotonic_now_ns() >= time_ns) return;
    timespec until{};
    until.tv_sec = static_cast<time_t>(time_ns / 1'000'000'000);
    until.tv_nsec = static_cast<long>(time_ns % 1'000'000'000);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) != 0) {
    }
  }
  void spin_until(std::int64_t time_ns) noexcept override {
    while (monotonic_now_ns() < time_ns) {
    }
  }
};

}  // namespace

LoopClock& monotonic_loop_clock() noexcept {
  static MonotonicLoopClock clock;
  return clock;
}

}  // namespace hapscene
