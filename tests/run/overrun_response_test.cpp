// What passing the overrun limits does: a device with a motor stops (zero force, a fault);
// a simulated device, whose world waits for the loop, reports the crossing and runs on
// (RunOptions::overruns; Device::deadlines_matter). The live view learns both through the
// LoopMonitor. On a SteppedClock: exact on any machine.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdint>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/runner.hpp"
#include "tests/run/slow_device.hpp"
#include "tests/run/stepped_clock.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

// A run whose wake-up 101 comes 30 ms late and whose tick 200 takes 30 ms of its own: on a
// device with a motor, the second is a sustained overrun.
template <typename MakeDevice>
RunSummary run_with_overruns(OverrunResponse response, LoopMonitor* monitor, MakeDevice&& make_device) {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 300}]})");
  test::SteppedClock clock;
  auto device = make_device(scene, clock);
  const RunOptions options{.duration_s = 0.5, .pacing = Pacing::real_time, .overruns = response,
                           .monitor = monitor, .clock = &clock};
  return run_scene(scene, device, options, nullptr);
}

test::SlowDevice slow_at_200(const Scene& scene, test::SteppedClock& clock) {
  return test::SlowDevice(scene, clock, [](std::uint64_t tick) { return tick == 200; }, std::chrono::milliseconds(30));
}

// The simulated Hapkit itself, whose ticks take 30 ms of the loop's own time at tick 200
// (a wrapper that keeps what the Hapkit says of its deadlines).
class SlowSimulated final : public Device {
 public:
  SlowSimulated(const Scene& scene, test::SteppedClock& clock) : inner_(scene.device, SimulationConfig{}), clock_(clock) {}
  std::int32_t read() noexcept override {
    if (ticks_ == 200) clock_.pass(30'000'000);
    return inner_.read();
  }
  void write(const MotorCommand& command) noexcept override { inner_.write(command); }
  void advance(double dt_s) noexcept override {
    ++ticks_;
    inner_.advance(dt_s);
  }
  bool deadlines_matter() const noexcept override { return inner_.deadlines_matter(); }

 private:
  SimulatedHapkit inner_;
  test::SteppedClock& clock_;
  std::uint64_t ticks_{};
};

}  // namespace

TEST_CASE("overruns: the simulated devices report them, the others stop on them") {
  SimulatedHapkit hapkit(scene_from(R"({"effects": []})").device, SimulationConfig{});
  CHECK_FALSE(hapkit.deadlines_matter());
}

TEST_CASE("overruns: a device with a motor stops on a sustained overrun, and the monitor says so") {
  LoopMonitor monitor;
  const RunSummary summary = run_with_overruns(OverrunResponse::by_device, &monitor, slow_at_200);
  CHECK(summary.overruns_stop);
  CHECK(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);
  CHECK(summary.ticks == 201);
  CHECK(monitor.overrun_kind() == OverrunFault::streak);
  CHECK(monitor.overrun_stopped());
  CHECK(monitor.overrun_t_s() == doctest::Approx(0.200));
  CHECK(monitor.end() == RunEnd::overrun_fault);
}

TEST_CASE("overruns: a simulated device reports the limit passed and runs to the end") {
  LoopMonitor monitor;
  const RunSummary summary =
      run_with_overruns(OverrunResponse::by_device, &monitor, [](const Scene& scene, test::SteppedClock& clock) {
        return SlowSimulated(scene, clock);
      });
  CHECK_FALSE(summary.overruns_stop);
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);  // passed, reported
  CHECK(summary.overrun_fault_s == doctest::Approx(0.200));
  CHECK(summary.deadline_misses == 30);
  CHECK(summary.ticks == 500);
  CHECK(monitor.overrun_kind() == OverrunFault::streak);
  CHECK_FALSE(monitor.overrun_stopped());
  CHECK(monitor.end() == RunEnd::duration);
}

TEST_CASE("overruns: asked to, a simulated run stops on them like a motor's") {
  const RunSummary summary =
      run_with_overruns(OverrunResponse::stop, nullptr, [](const Scene& scene, test::SteppedClock& clock) {
        return SlowSimulated(scene, clock);
      });
  CHECK(summary.overrun_fault);
  CHECK(summary.ticks == 201);
}

TEST_CASE("overruns: asked to, a device with a motor only reports them") {
  const RunSummary summary = run_with_overruns(OverrunResponse::report, nullptr, slow_at_200);
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);
  CHECK(summary.ticks == 500);
}

TEST_CASE("overruns: the monitor tells how a run without them ended") {
  const Scene scene = scene_from(R"({"effects": []})");
  test::SteppedClock clock;
  SimulatedHapkit device(scene.device, SimulationConfig{});
  LoopMonitor monitor;
  CHECK(monitor.end() == RunEnd::running);
  run_scene(scene, device, RunOptions{.duration_s = 0.05, .pacing = Pacing::real_time, .monitor = &monitor, .clock = &clock},
            nullptr);
  CHECK(monitor.end() == RunEnd::duration);
  CHECK(monitor.overrun_kind() == OverrunFault::none);
  std::atomic<bool> stop{true};
  LoopMonitor stopped;
  run_scene(scene, device,
            RunOptions{.duration_s = 0.05, .pacing = Pacing::real_time, .stop_requested = &stop, .monitor = &stopped,
                       .clock = &clock},
            nullptr);
  CHECK(stopped.end() == RunEnd::stop_requested);
}
