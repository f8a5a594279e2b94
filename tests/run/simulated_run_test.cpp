// Closed-loop runs on the simulated Hapkit: what the lab environments feel like, the
// soft start, and bit-for-bit determinism.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/runner.hpp"
#include "tests/run/slow_device.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

struct Sample {
  double t_s, x_true_m, x_m, v_m_per_s, force_N, output_N;
  bool operator==(const Sample&) const = default;
};

// Records every tick with the simulator's true position (reserved up front).
class Trace final : public TickObserver {
 public:
  Trace(const SimulatedHapkit& device, std::size_t ticks) : device_(device) { samples.reserve(ticks); }
  void on_tick(const TickState& s) noexcept override {
    samples.push_back({s.t_s, device_.x_m(), s.x_m, s.v_m_per_s, s.effects_force_N, s.output_N});
  }
  std::vector<Sample> samples;

 private:
  const SimulatedHapkit& device_;
};

struct Result {
  RunSummary summary;
  std::vector<Sample> samples;
};

Result simulate(const Scene& scene, SimulationConfig config, double duration_s,
                double noise_counts = 0.0) {
  DeviceProfile profile = scene.device;
  profile.plant.sensor_noise_counts = noise_counts;
  SimulatedHapkit device(profile, config);
  Trace trace(device, static_cast<std::size_t>(duration_s * scene.rate_hz) + 1);
  RunOptions options{.duration_s = duration_s, .pacing = Pacing::simulated_time};
  Result result{run_scene(scene, device, options, &trace), {}};
  result.samples = std::move(trace.samples);
  return result;
}

}  // namespace

TEST_CASE("sim: a hand sweeping into the lab wall is pushed back, stably") {
  const Scene scene = load_environment_file(test::source_path("environments/wall.json"));
  SimulationConfig config;  // sweep to +/- 40 mm with a 200 N/m hand
  const Result run = simulate(scene, config, 2.0);
  CHECK(run.summary.ticks == 2000);
  double deepest_m = 0.0;
  for (const Sample& s : run.samples) {
    deepest_m = std::max(deepest_m, s.x_true_m - 0.010);
    // Outside the wall no force; inside, -K * penetration of the measured position.
    if (s.x_m < 0.010) CHECK(s.force_N == 0.0);
    else CHECK(s.force_N == doctest::Approx(-500.0 * (s.x_m - 0.010)));
  }
  // Hand and wall springs in series: 200 / (200 + 500) of the 30 mm the hand asks for.
  CHECK(deepest_m == doctest::Approx(0.030 * 200.0 / 700.0).epsilon(0.1));
  CHECK(run.summary.safety.nonfinite_faults == 0);
  CHECK(run.summary.safety.clamped_ticks == 0);
}

TEST_CASE("sim: a released spring oscillates at its natural frequency and decays") {
  const Scene scene = load_environment_file(test::source_path("environments/spring.json"));
  const double stiffness_N_per_m = std::get<Spring>(scene.effects[0]).stiffness_N_per_m;
  SimulationConfig config;
  config.hand.motion = HandMotion::release;  // hold at 20 mm, let go at 0.5 s
  config.hand.hold_m = 0.020;
  config.hand.release_s = 0.5;
  const Result run = simulate(scene, config, 2.0);
  // Zero crossings of the true position after the release: half periods.
  std::vector<double> crossings_s;
  for (std::size_t i = 1; i < run.samples.size(); ++i) {
    if ((run.samples[i - 1].x_true_m < 0.0) != (run.samples[i].x_true_m < 0.0)) {
      crossings_s.push_back(run.samples[i].t_s);
    }
  }
  REQUIRE(crossings_s.size() >= 3);
  CHECK(crossings_s[0] > 0.5);
  const double period_s = crossings_s[2] - crossings_s[0];
  const double natural_period_s = 2.0 * M_PI / std::sqrt(stiffness_N_per_m / scene.device.plant.mass_kg);
  CHECK(period_s == doctest::Approx(natural_period_s).epsilon(0.05));
  // Friction and damping take the energy out: it ends at rest within the friction band.
  const double band_m = scene.device.plant.coulomb_N / stiffness_N_per_m;
  CHECK(std::abs(run.samples.back().x_true_m) <= band_m);
  CHECK(run.samples.back().v_m_per_s == doctest::Approx(0.0).epsilon(1e-3));
}

TEST_CASE("sim: starting inside a wall ramps the force in instead of a jolt") {
  const Scene scene = scene_from(R"({"effects": [
    {"type": "wall", "position": 0, "stiffness": 1000, "solid": "above"}]})");
  SimulationConfig config;
  config.start_x_m = 0.004;  // 4 N asked at the first tick
  config.hand.motion = HandMotion::none;
  const Result run = simulate(scene, config, 1.0);
  CHECK(run.samples[0].force_N < -3.5);
  CHECK(run.samples[0].output_N == 0.0);
  CHECK(run.summary.safety.soft_start_ticks > 0);
  CHECK(run.summary.safety.slew_limited_ticks == 0);
  double largest_step_N = 0.0;
  for (std::size_t i = 1; i < run.samples.size(); ++i) {
    largest_step_N = std::max(largest_step_N, std::abs(run.samples[i].output_N - run.samples[i - 1].output_N));
  }
  CHECK(largest_step_N < 0.05);
  CHECK(run.samples.back().x_true_m < 0.0005);  // pushed out of the wall
}

TEST_CASE("sim: two runs with the same inputs are identical to the last bit") {
  const Scene scene = load_environment_file(test::source_path("environments/wall_corridor.json"));
  SimulationConfig config;
  config.noise_seed = 42;
  const Result a = simulate(scene, config, 1.0, /*noise_counts=*/1.5);
  const Result b = simulate(scene, config, 1.0, 1.5);
  CHECK(a.samples == b.samples);
  config.noise_seed = 43;
  const Result c = simulate(scene, config, 1.0, 1.5);
  CHECK_FALSE(a.samples == c.samples);
}

TEST_CASE("sim: a start outside the sensor's home period is refused") {
  const Scene scene = scene_from(R"({"effects": []})");
  SimulationConfig config;
  config.start_x_m = 0.02;
  CHECK(test::input_error_of([&] { SimulatedHapkit device(scene.device, config); }) ==
        "start position 0.02 m is outside the sensor's home period [-0.006232220045, 0.005060928469] m, "
        "where the board starts counting (the period from hapkit3 (built-in profile): /sensor)");
}

TEST_CASE("sim: the motor saturates and the PWM is quantized") {
  const Scene scene = scene_from(R"({"effects": []})");
  SimulationConfig config;
  config.hand.motion = HandMotion::none;
  SimulatedHapkit device(scene.device, config);
  device.write(MotorCommand{.duty = 2.0, .direction_high = true});
  CHECK(device.motor_force_N() == doctest::Approx(max_motor_force_N(scene.device)));
  device.write(MotorCommand{.duty = 0.5 / 255.0 + 1e-9, .direction_high = false});
  CHECK(device.motor_force_N() == doctest::Approx(-motor_to_force_N(scene.device, {1.0 / 255.0, true})));
}

TEST_CASE("sim: Coulomb friction holds the handle against small forces") {
  const Scene scene = scene_from(R"({"effects": []})");
  SimulationConfig config;
  config.hand.motion = HandMotion::none;
  SimulatedHapkit device(scene.device, config);
  device.write(force_to_motor(scene.device, 0.08));  // below 0.1 N of friction
  for (int i = 0; i < 100; ++i) device.advance(0.001);
  CHECK(device.x_m() == 0.0);
  device.write(force_to_motor(scene.device, 0.3));
  for (int i = 0; i < 100; ++i) device.advance(0.001);
  CHECK(device.x_m() > 0.001);
}

TEST_CASE("run: real-time pacing keeps absolute deadlines and counts its timing" * doctest::test_suite("timing")) {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 50}]})");
  SimulationConfig config;
  SimulatedHapkit device(scene.device, config);
  RunOptions options{.duration_s = 0.05, .pacing = Pacing::real_time};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.ticks == 50);
  CHECK(summary.wake_late_ns.count() == 50);
  CHECK(summary.compute_ns.count() == 50);
  CHECK(summary.wall_time_s >= 0.049);  // 50 deadlines 1 ms apart cannot finish early
}

TEST_CASE("run: a stop request ends the run at the next tick" * doctest::test_suite("timing")) {
  const Scene scene = scene_from(R"({"effects": []})");
  SimulatedHapkit device(scene.device, SimulationConfig{});
  std::atomic<bool> stop{true};
  RunOptions options{.duration_s = 10.0, .pacing = Pacing::real_time, .stop_requested = &stop};
  CHECK(run_scene(scene, device, options, nullptr).ticks == 0);
}

TEST_CASE("latency histogram: percentiles within 3 %, exact max") {
  LatencyHistogram histogram;
  for (std::uint64_t ns = 1; ns <= 10000; ++ns) histogram.record(ns);
  CHECK(histogram.count() == 10000);
  CHECK(histogram.max_ns() == 10000);
  CHECK(static_cast<double>(histogram.percentile_ns(0.5)) == doctest::Approx(5000).epsilon(0.03));
  CHECK(static_cast<double>(histogram.percentile_ns(0.99)) == doctest::Approx(9900).epsilon(0.03));
  CHECK(histogram.percentile_ns(1.0) == 10000);
}

// The overrun cases run on a SteppedClock: each slow tick takes exactly the time asked,
// so the misses, warnings and faults below are exact on any machine.
TEST_CASE("run: sustained overruns warn, then fault to zero force and stop") {
  // From tick 20 on each tick takes 1.6 periods: one miss a tick, a streak growing by one.
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 500}]})");
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick >= 20; });
  RunOptions options{.duration_s = 0.2, .pacing = Pacing::real_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.overrun_fault);
  CHECK(summary.overruns_stop);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);
  CHECK(summary.overrun_warnings == 1);
  CHECK(summary.first_overrun_warning_s == doctest::Approx(0.022));  // the third miss in a row
  CHECK(summary.overrun_fault_s == doctest::Approx(0.029));          // the tenth
  CHECK(summary.longest_miss_streak == 10);
  CHECK(summary.deadline_misses == 10);
  CHECK(summary.ticks == 30);  // stopped, not run to 200 ticks
  CHECK(device.last.duty == 0.0);
  CHECK_FALSE(summary.realtime_note.empty());
}

TEST_CASE("run: a short burst of overruns warns without a fault") {
  const Scene scene = scene_from(R"({"effects": []})");
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick >= 10 && tick < 14; });
  RunOptions options{.duration_s = 0.06, .pacing = Pacing::real_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::none);
  CHECK(summary.overrun_warnings == 1);
  CHECK(summary.longest_miss_streak == 4);
  CHECK(summary.deadline_misses == 4);
  CHECK(summary.ticks == 60);  // ran on; realigned schedules skip the missed deadlines
}

TEST_CASE("run: one stall of many periods is that many misses in a row: a fault, zero force") {
  // A tick that takes 30 periods (a script slow but within its budget, a blocked device)
  // leaves the motor without a command for 30 deadlines: a sustained overrun.
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 500}]})");
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick == 20; }, std::chrono::milliseconds(30));
  RunOptions options{.duration_s = 0.2, .pacing = Pacing::real_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);
  CHECK(summary.deadline_misses == 30);
  CHECK(summary.longest_miss_streak == 30);
  CHECK(summary.stall_misses == 0);
  CHECK(summary.ticks == 21);
  CHECK(device.last.duty == 0.0);
}

TEST_CASE("run: single overruns neither warn nor fault") {
  const Scene scene = scene_from(R"({"effects": []})");
  // 1.2 ms: each slow tick misses its deadline, and the loop is back on time 0.8 ms later.
  test::SteppedClock clock;
  test::SlowDevice device(scene, clock, [](std::uint64_t tick) { return tick % 10 == 5; },
                          std::chrono::microseconds(1200));
  RunOptions options{.duration_s = 0.05, .pacing = Pacing::real_time, .clock = &clock};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(summary.deadline_misses == 5);
  CHECK(summary.longest_miss_streak == 1);
  CHECK(summary.overrun_warnings == 0);
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.ticks == 50);
}

TEST_CASE("latency histogram: counts below an edge") {
  LatencyHistogram histogram;
  for (std::uint64_t ns = 1; ns <= 1000; ++ns) histogram.record(ns * 1000);
  CHECK(histogram.count_at_most(0) == 0);
  CHECK(histogram.count_at_most(2'000'000) == 1000);
  CHECK(std::abs(static_cast<double>(histogram.count_at_most(500'000)) - 500.0) <= 500.0 * 0.03 + 1);
}
