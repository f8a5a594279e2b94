// An isolated stall of the system (the OS or the VM does not run the loop for a while) is
// counted and warned of, but is not a sustained overrun: the fault streak counts only the
// misses the loop's own work makes (tests/run/simulated_run_test.cpp: a tick of the loop's
// own that takes 30 periods still faults). On a SteppedClock, whose wake-up 101 comes 25 ms
// late: the same counts on any machine. (The loop sleeps until 50 us before a deadline, so
// that wake-up is 24.95 ms past tick 100's deadline: 24 deadlines missed.)
#include <doctest/doctest.h>

#include <cstdint>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/runner.hpp"
#include "tests/run/stepped_clock.hpp"
#include "tests/support.hpp"

using namespace hapscene;

TEST_CASE("run: an isolated stall of the system warns without a fault") {
  const Scene scene = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 200}]})");
  test::SteppedClock clock;
  clock.make_wake_ups_late([](std::uint64_t wake_up) { return wake_up == 101 ? std::int64_t{25'000'000} : 0; });
  SimulatedHapkit device(scene.device, SimulationConfig{});
  // Stopping on overruns, as with a motor: the stall must not be taken for one.
  const RunOptions options{.duration_s = 0.4, .pacing = Pacing::real_time, .overruns = OverrunResponse::stop,
                           .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::none);
  CHECK(summary.deadline_misses == 24);
  CHECK(summary.stall_misses == 24);
  CHECK(summary.longest_miss_streak == 24);  // more than the 10 that fault an overrun of the loop's own
  CHECK(summary.overrun_warnings == 1);
  CHECK(summary.first_overrun_warning_s == doctest::Approx(0.100));
  CHECK(summary.ticks == 400);  // ran on to the end
}

TEST_CASE("run: stalls of the system that come often fault as frequent misses") {
  // Every other wake-up 1.5 periods late: a stall miss every two ticks, never the loop's
  // own, never a streak; the 101st miss is a fault of the window (a machine that cannot
  // keep the rate leaves a motor at half of it).
  const Scene scene = test::scene_from(R"({"effects": []})");
  test::SteppedClock clock;
  clock.make_wake_ups_late([](std::uint64_t wake_up) { return wake_up % 2 == 0 ? std::int64_t{1'500'000} : 0; });
  SimulatedHapkit device(scene.device, SimulationConfig{});
  const RunOptions options{.duration_s = 1.0, .pacing = Pacing::real_time, .overruns = OverrunResponse::stop,
                           .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::window);
  CHECK(summary.stall_misses == summary.deadline_misses);
  CHECK(summary.deadline_misses == 101);
  CHECK(summary.longest_miss_streak == 1);
  CHECK(summary.ticks == 202);
}
