// The runner's second overrun criterion: too many deadline misses within a sliding window
// of deadlines, for slow ticks that come periodically and never make a streak.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdint>
#include <functional>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/runner.hpp"
#include "tests/run/slow_device.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

TEST_CASE("run: every third tick overrunning by two periods is a fault of frequent overruns") {
  // Each slow tick misses 2 deadlines, then two ticks keep time: never 10 in a row, yet the
  // device gets 3 commands in 5 periods. Default numbers: > 100 misses in 1000 deadlines.
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 500}]})");
  // Per three ticks: 2 deadlines missed, 2 met; the 101st miss comes with the 51st slow
  // tick (tick 152).
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick % 3 == 2; },
                          std::chrono::microseconds(2600));
  const RunOptions options{.duration_s = 2.0, .pacing = Pacing::real_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::window);
  CHECK(summary.longest_miss_streak == 2);
  CHECK(summary.overrun_warnings == 0);
  CHECK(summary.most_misses_in_window == 102);
  CHECK(summary.ticks == 153);  // stopped, not run to 2000 ticks
  CHECK(summary.overrun_fault_s == doctest::Approx(0.152));
  CHECK(device.last.duty == 0.0);
}

TEST_CASE("run: misses spread thinner than the window's limit never fault, however many in all") {
  // One miss every 15 deadlines: at most 14 in any 200 (limit 20), 40 in the run (more
  // than 20): the window slides, old misses leave it.
  const Scene scene = scene_from(R"({"effects": []})");
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick % 15 == 7; },
                          std::chrono::microseconds(1500));
  const RunOptions options{.duration_s = 0.6,
                           .pacing = Pacing::real_time,
                           .overrun_window_deadlines = 200,
                           .overrun_window_misses = 20,
                           .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::none);
  CHECK(summary.deadline_misses == 40);
  CHECK(summary.most_misses_in_window == 14);
  CHECK(summary.ticks == 600);
}

TEST_CASE("run: a streak still faults as a streak, not as frequent overruns") {
  const Scene scene = scene_from(R"({"effects": []})");
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick == 20; }, std::chrono::milliseconds(30));
  const RunOptions options{.duration_s = 0.2, .pacing = Pacing::real_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);
}

TEST_CASE("run: simulated time never counts overruns") {
  const Scene scene = scene_from(R"({"effects": []})");
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick % 3 == 2; },
                          std::chrono::microseconds(2600));
  const RunOptions options{.duration_s = 0.3, .pacing = Pacing::simulated_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.ticks == 300);
}
