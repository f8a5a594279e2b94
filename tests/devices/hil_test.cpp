// Firmware-in-the-loop: the real firmware (build/firmware/hapkit_firmware.elf) on
// simavr's ATmega328P, wired to the simulated Hapkit, driven by the host engine through
// the same protocol code as a real board. Compiled only when the build has simavr and
// the AVR toolchain; otherwise one skipped case says so.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/devices/open_device.hpp"
#include "tests/support.hpp"

#if HAPSCENE_HAVE_HIL
#include "engine/devices/hil/hil_hapkit.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/runner.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

HilConfig hil_config(const SimulationConfig& simulation) {
  HilConfig config;
  config.simulation = simulation;
  config.firmware_elf = default_firmware_elf();
  return config;
}

struct Sample {
  double x_true_m, x_m, output_N, motor_force_N;
  bool operator==(const Sample&) const = default;
};

// Records each tick; `true_x` and `motor` read the device after its previous advance.
template <class DeviceT>
class Trace final : public TickObserver {
 public:
  Trace(const DeviceT& device, std::size_t ticks) : device_(device) { samples.reserve(ticks); }
  void on_tick(const TickState& s) noexcept override {
    samples.push_back({device_.x_m(), s.x_m, s.output_N, device_.motor_force_N()});
  }
  std::vector<Sample> samples;

 private:
  const DeviceT& device_;
};

template <class DeviceT>
std::vector<Sample> run(const Scene& scene, DeviceT& device, double duration_s,
                        TickObserver* extra = nullptr) {
  Trace<DeviceT> trace(device, static_cast<std::size_t>(duration_s * scene.rate_hz) + 1);
  struct Both final : TickObserver {
    TickObserver* a;
    TickObserver* b;
    void on_tick(const TickState& s) noexcept override {
      a->on_tick(s);
      if (b != nullptr) b->on_tick(s);
    }
  } both;
  both.a = &trace;
  both.b = extra;
  RunOptions options{.duration_s = duration_s, .pacing = Pacing::simulated_time};
  run_scene(scene, device, options, &both);
  return trace.samples;
}

}  // namespace

TEST_CASE("hil: a wall contact renders the same forces as the simulated device" * doctest::test_suite("threaded")) {
  const Scene scene = load_environment_file(test::source_path("environments/wall.json"));
  SimulationConfig simulation;  // the hand sweeps to +/- 40 mm
  SimulatedHapkit sim(scene.device, simulation);
  HilHapkit hil(scene.device, hil_config(simulation));
  const auto a = run(scene, sim, 1.0);
  const auto b = run(scene, hil, 1.0);
  REQUIRE(a.size() == b.size());

  // The same contact: peak force and depth within 2 %, the force along the way within
  // what one tick of extra latency (the board's reply arrives for the next tick) and
  // one PWM step explain.
  double peak_a = 0.0, peak_b = 0.0, worst_N = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    peak_a = std::max(peak_a, std::abs(a[i].output_N));
    peak_b = std::max(peak_b, std::abs(b[i].output_N));
    worst_N = std::max(worst_N, std::abs(a[i].output_N - b[i].output_N));
  }
  MESSAGE("peak force sim " << peak_a << " N, hil " << peak_b << " N; largest difference " << worst_N << " N");
  CHECK(peak_a > 3.0);
  CHECK(peak_b == doctest::Approx(peak_a).epsilon(0.02));
  CHECK(worst_N < 0.1);

  // The board drives what the host commands, within one PWM step (the host rounds the
  // duty to 1/255, the timer to 1/256; force ~ duty^2): the motor force after each tick
  // against that tick's command.
  for (std::size_t i = 1; i < b.size(); ++i) {
    const double commanded_N = b[i - 1].output_N;
    const double step_N = 2.0 * std::sqrt(std::abs(commanded_N) * max_motor_force_N(scene.device)) / 255.0;
    CHECK(std::abs(b[i].motor_force_N - commanded_N) <= step_N + 1e-9);
  }
}

TEST_CASE("hil: the board turns the motor off within its timeout when the host stops talking" * doctest::test_suite("threaded")) {
  const Scene scene = scene_from(R"({"effects": []})");
  SimulationConfig simulation;
  simulation.hand.motion = HandMotion::hold;
  simulation.hand.stiffness_N_per_m = 2000.0;
  HilHapkit hil(scene.device, hil_config(simulation));
  for (int i = 0; i < 20; ++i) {
    hil.read();
    hil.write(MotorCommand{0.5, true});
    hil.advance(0.001);
  }
  CHECK(hil.motor_duty() == doctest::Approx(129.0 / 256.0));  // 128/255 to the nearest count

  // The host goes quiet: the motor must stop 20 ms after the last command, not earlier.
  hil.read();
  hil.write(MotorCommand{0.5, true});
  hil.wire().host_silent = true;
  double off_after_s = -1.0;
  for (int i = 0; i < 400 && off_after_s < 0.0; ++i) {
    hil.advance(0.0001);
    if (hil.motor_duty() == 0.0) off_after_s = (i + 1) * 0.0001;
  }
  MESSAGE("motor off " << off_after_s * 1e3 << " ms after the last command");
  CHECK(off_after_s >= 0.0195);
  CHECK(off_after_s <= 0.0205 + 0.0002 + 0.0004);  // + one sample period + the frame's transit

  // The host sees the silence too, and the board counted the timeout.
  for (int i = 0; i < 60; ++i) {
    hil.read();
    hil.advance(0.001);
  }
  CHECK(hil.link().state() == LinkState::silent);
  hil.wire().host_silent = false;
  for (int i = 0; i < 30; ++i) {
    hil.read();
    hil.write(MotorCommand{0.0, false});
    hil.advance(0.001);
  }
  CHECK(hil.link().state() == LinkState::running);
  hil.mutable_link().request_stats();
  hil.advance(0.002);
  hil.read();
  CHECK(hil.link().board_stats().timeouts == 1);
}

TEST_CASE("hil: corrupt bytes, dropped bytes, garbage and a board reset are survived" * doctest::test_suite("threaded")) {
  const Scene scene = scene_from(R"({"effects": [
    {"type": "wall", "position": 0, "stiffness": 500, "solid": "above"}]})");
  SimulationConfig simulation;
  simulation.hand.motion = HandMotion::hold;
  simulation.hand.hold_m = 0.004;
  simulation.hand.stiffness_N_per_m = 1000.0;
  HilHapkit hil(scene.device, hil_config(simulation));

  // Faults at chosen ticks, from inside the run.
  struct Faults final : TickObserver {
    HilHapkit* hil;
    std::uint64_t tick{};
    void on_tick(const TickState&) noexcept override {
      Wire& wire = hil->wire();
      switch (++tick) {
        case 100: wire.to_board.corrupt_in = 5, wire.to_board.corrupt_mask = 0x08; break;
        case 150: wire.to_board.drop_next = 3; break;
        case 200: wire.to_host.corrupt_in = 7, wire.to_host.corrupt_mask = 0x80; break;
        case 250: wire.to_host.drop_next = 4; break;
        case 300: {
          const std::uint8_t garbage[] = {0xA5, 0xFF, 0x00, 0xA5, 0x02, 0x07, 0x13};
          wire.inject_to_board(garbage, sizeof garbage);
          break;
        }
        case 400: hil->reset_board(); break;
        default: break;
      }
    }
  } faults;
  faults.hil = &hil;
  const auto samples = run(scene, hil, 1.0, &faults);

  const BoardLink& link = hil.link();
  CHECK(link.state() == LinkState::running);
  CHECK(link.decoder().crc_errors >= 1);
  CHECK(link.counters().seq_gaps >= 1);
  bool saw_reset = false;
  for (std::size_t i = 0; i < link.event_count(); ++i) saw_reset |= link.event(i).kind == LinkEventKind::board_reset;
  CHECK(saw_reset);
  // The board counted what reached it broken (after its reset, so only the garbage here).
  hil.mutable_link().request_stats();
  hil.advance(0.002);
  hil.read();
  CHECK(link.board_stats().frames_ok > 100);

  // The position stayed right and the wall pushes again after the reset's ramp-in:
  // the hand (1000 N/m at 4 mm) and the wall (500 N/m) balance at 2.67 mm, 1.33 N.
  const Sample& last = samples.back();
  CHECK(std::abs(last.x_m - last.x_true_m) < 2e-5);
  CHECK(last.output_N == doctest::Approx(-1.333).epsilon(0.05));
  // No jolt, faults or not: the force never rises by more than 0.1 N in a tick (after
  // the reset it drops to zero and ramps in again over the soft start). From tick 50 on:
  // before that the hand pushes the handle from 0 into the wall, and the wall's force
  // rises with the handle (the run starts outside the wall, so without a soft start,
  // now that the first tick uses the measured position rather than a default one).
  double largest_rise_N = 0.0;
  for (std::size_t i = 50; i < samples.size(); ++i) {
    largest_rise_N = std::max(largest_rise_N, std::abs(samples[i].output_N) - std::abs(samples[i - 1].output_N));
  }
  CHECK(largest_rise_N < 0.1);
}

TEST_CASE("hil: runs are deterministic and the firmware reports its timing in cycles" * doctest::test_suite("threaded")) {
  const Scene scene = load_environment_file(test::source_path("environments/spring.json"));
  SimulationConfig simulation;
  HilHapkit a(scene.device, hil_config(simulation));
  HilHapkit b(scene.device, hil_config(simulation));
  const auto run_a = run(scene, a, 0.5);
  const auto run_b = run(scene, b, 0.5);
  CHECK(run_a == run_b);

  REQUIRE(a.link().has_stats());
  const hs_stats& stats = a.link().board_stats();
  MESSAGE("firmware: sampler interrupt max " << stats.sampler_cycles_max << " cycles, main loop pass max "
          << stats.loop_cycles_max << " cycles; round trip p50 "
          << static_cast<double>(a.link().round_trip_ns().percentile_ns(0.5)) / 1000.0 << " us");
  CHECK(stats.sampler_cycles_max > 50);
  CHECK(stats.sampler_cycles_max < 3200);  // well inside the 200 us sample period
  CHECK(stats.loop_cycles_max > 0);
  CHECK(a.report().find("firmware timing  sampler interrupt max") != std::string::npos);
}

#else

TEST_CASE("hil: firmware-in-the-loop tests" * doctest::skip()) {
  MESSAGE("skipped: this build has no simavr or AVR toolchain "
          "(apt-get install gcc-avr avr-libc binutils-avr simavr libsimavr-dev, then re-run cmake)");
}

#endif

}  // namespace HAPSCENE_TEST_FILE
