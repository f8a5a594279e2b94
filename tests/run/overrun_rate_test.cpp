// The overrun limits stand for the same time at any rate above 1 kHz: a stall of a few
// milliseconds (a desktop's or a VM's) faults a 10 kHz run no sooner than a 1 kHz one,
// while overruns that go on still fault.
#include <doctest/doctest.h>

#include <chrono>

#include "engine/run/runner.hpp"
#include "tests/run/slow_device.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

TEST_CASE("overrun limits: unchanged up to 1 kHz, scaled to the same time above it") {
  const RunOptions options;
  for (const double rate_hz : {100.0, 500.0, 1000.0}) {
    const OverrunLimits limits = overrun_limits_at(options, rate_hz);
    CHECK(limits.warn_ticks == options.overrun_warn_ticks);
    CHECK(limits.fault_ticks == options.overrun_fault_ticks);
    CHECK(limits.window_deadlines == options.overrun_window_deadlines);
    CHECK(limits.window_misses == options.overrun_window_misses);
  }
  // 10 kHz: 10 ms without a command in a row (100 deadlines), > 100 ms of misses in 1 s.
  const OverrunLimits fast = overrun_limits_at(options, 10'000.0);
  CHECK(fast.warn_ticks == 30);
  CHECK(fast.fault_ticks == 100);
  CHECK(fast.window_deadlines == 10'000);
  CHECK(fast.window_misses == 1000);
  // The window holds at most kMaxOverrunWindow deadlines.
  CHECK(overrun_limits_at(options, 100'000.0).window_deadlines == kMaxOverrunWindow);
}

TEST_CASE("run at 10 kHz: overruns that go on still fault") {
  // Every tick takes 2 ms at a 0.1 ms period: 20 misses per tick, a streak of 100 after
  // five ticks.
  const Scene scene = scene_from(R"({"rate_hz": 10000, "effects": []})");
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t) { return true; }, std::chrono::milliseconds(2));
  const RunOptions options{.duration_s = 1.0, .pacing = Pacing::real_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);
  CHECK(summary.overrun_limits.fault_ticks == 100);
  CHECK(summary.deadline_misses == 100);
  CHECK(summary.ticks == 5);
  CHECK(device.last.duty == 0.0);
}
