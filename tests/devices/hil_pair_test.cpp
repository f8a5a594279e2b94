// Firmware-in-the-loop for 2-DOF scenes: two simulated boards, each the real firmware on
// simavr's ATmega328P, as the two joints of a Hapkit pantograph, wired to the simulated
// five-bar in lock-step and judged as one device (BoardPair). Compiled only when the build
// has simavr and the AVR toolchain; otherwise one skipped case says so.
#include <doctest/doctest.h>

#include <signal.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/devices/open_device.hpp"
#include "tests/support.hpp"

#if HAPSCENE_HAVE_HIL
#include "engine/devices/hil/hil_pair.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/observer_list.hpp"
#include "engine/run/runner.hpp"

using namespace hapscene;

namespace {

// A solid box right of the pantograph's home (50, 132.5) mm; the hand drives the handle
// 20 mm right, into it, and back.
constexpr const char* kBoxScene = R"({"device": "hapkit_pantograph", "effects": [
  {"type": "box", "min": ["60 mm", "115 mm"], "max": ["100 mm", "150 mm"], "stiffness": "400 N/m", "solid": "inside"}]})";

PlanarSimulationConfig line_into_box(const PlanarScene& scene) {
  PlanarSimulationConfig config;
  config.start_q_rad = planar_joint_angles_at(scene.device, scene.device.home_m);
  config.hand.motion = PlanarHandMotion::line;
  config.hand.line_from_m = scene.device.home_m;
  config.hand.line_to_m = scene.device.home_m + Vec2{{0.020, 0.0}};
  config.hand.line_back_and_forth = true;
  config.hand.speed_m_per_s = 0.04;
  config.hand.stiffness_N_per_m = 1500.0;
  return config;
}

// The hand holds the handle 4 mm into the box (1000 N/m against the box's 400 N/m).
PlanarSimulationConfig held_in_box(const PlanarScene& scene) {
  PlanarSimulationConfig config;
  config.start_q_rad = planar_joint_angles_at(scene.device, scene.device.home_m);
  config.hand.motion = PlanarHandMotion::hold;
  config.hand.hold_m = scene.device.home_m + Vec2{{0.014, 0.0}};
  config.hand.stiffness_N_per_m = 1000.0;
  return config;
}

HilPairConfig pair_hil_config(const PlanarSimulationConfig& simulation) {
  HilPairConfig config;
  config.simulation = simulation;
  config.firmware_elf = default_firmware_elf();
  return config;
}

struct PairSample {
  Vec2 x_true_m, x_m, output_N, motor_force_N;
  bool operator==(const PairSample&) const = default;
};

// Records each tick; the truth is read after the device's previous advance.
class PairTrace final : public TickObserverOf<2> {
 public:
  PairTrace(const SimulationTruthOf<2>& truth, std::size_t ticks) : truth_(truth) { samples.reserve(ticks); }
  void on_tick(const TickStateOf<2>& s) noexcept override {
    samples.push_back({truth_.x_m(), s.x_m, s.output_N, truth_.motor_force_N()});
  }
  std::vector<PairSample> samples;

 private:
  const SimulationTruthOf<2>& truth_;
};

std::vector<PairSample> run_pair(const PlanarScene& scene, DeviceOf<2>& device, double duration_s,
                        TickObserverOf<2>* extra = nullptr) {
  PairTrace trace(*device.truth(), static_cast<std::size_t>(duration_s * scene.rate_hz) + 1);
  ObserverListOf<2> observers;
  observers.add(&trace);
  if (extra != nullptr) observers.add(extra);
  RunOptions options{.duration_s = duration_s, .pacing = Pacing::simulated_time};
  run_scene(scene, device, options, &observers);
  return trace.samples;
}

double pair_largest_rise_N(const std::vector<PairSample>& samples, std::size_t from) {
  double rise_N = 0.0;
  for (std::size_t i = std::max<std::size_t>(from, 1); i < samples.size(); ++i) {
    rise_N = std::max(rise_N, norm(samples[i].output_N) - norm(samples[i - 1].output_N));
  }
  return rise_N;
}

}  // namespace

TEST_CASE("hil pair: a box contact renders the same forces as the simulated pantograph" *
          doctest::test_suite("threaded")) {
  const PlanarScene scene = load_planar_environment_text(kBoxScene, "box.json");
  const PlanarSimulationConfig simulation = line_into_box(scene);
  SimulatedPlanar sim(scene.device, simulation);
  HilPair hil(scene.device, pair_hil_config(simulation));
  const auto a = run_pair(scene, sim, 1.5);
  const auto b = run_pair(scene, hil, 1.5);
  REQUIRE(a.size() == b.size());

  // The same contact: peak force within 3 %, the force along the way within what a tick
  // of extra latency (each board's reply arrives for the next tick), the MR sensors'
  // quantization and a PWM step explain.
  double peak_a = 0.0, peak_b = 0.0, worst_N = 0.0, worst_m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    peak_a = std::max(peak_a, norm(a[i].output_N));
    peak_b = std::max(peak_b, norm(b[i].output_N));
    worst_N = std::max(worst_N, norm(a[i].output_N - b[i].output_N));
    // The measured position from the first board states on (tick 0 has none yet).
    if (i >= 2) worst_m = std::max(worst_m, norm(b[i].x_m - b[i].x_true_m));
  }
  MESSAGE("peak force sim " << peak_a << " N, hil " << peak_b << " N; largest difference " << worst_N
                            << " N; largest position error " << worst_m * 1e3 << " mm");
  CHECK(peak_a > 1.5);
  CHECK(peak_b == doctest::Approx(peak_a).epsilon(0.03));
  CHECK(worst_N < 0.15);
  CHECK(worst_m < 0.5e-3);
  // The box pushes back along -x.
  const auto deepest = std::max_element(b.begin(), b.end(), [](const PairSample& p, const PairSample& q) {
    return norm(p.output_N) < norm(q.output_N);
  });
  CHECK(deepest->output_N[0] < -1.0);
  CHECK(std::abs(deepest->output_N[1]) < 0.2 * std::abs(deepest->output_N[0]));

  // Both boards drive what the host commands: after the run's soft start the motors' force
  // at the handle follows the commanded force of the tick before within quantization.
  double worst_motor_N = 0.0;
  for (std::size_t i = 600; i < b.size(); ++i) {
    worst_motor_N = std::max(worst_motor_N, norm(b[i].motor_force_N - b[i - 1].output_N));
  }
  MESSAGE("motor force against the previous tick's command: worst " << worst_motor_N << " N");
  CHECK(worst_motor_N < 0.1);
  CHECK_FALSE(hil.fault_seen());
}

TEST_CASE("hil pair: faults on either board are survived, both motors zero meanwhile, no jolt" *
          doctest::test_suite("threaded")) {
  const PlanarScene scene = load_planar_environment_text(kBoxScene, "box.json");
  const PlanarSimulationConfig simulation = held_in_box(scene);
  HilPair hil(scene.device, pair_hil_config(simulation));

  // Faults at chosen ticks, on joint 2's board and then joint 1's, from inside the run.
  struct Faults final : TickObserverOf<2> {
    HilPair* hil;
    std::uint64_t tick{};
    void on_tick(const TickStateOf<2>&) noexcept override {
      Wire& wire_1 = hil->wire(0);
      Wire& wire_2 = hil->wire(1);
      switch (++tick) {
        case 700: wire_2.to_board.corrupt_in = 5, wire_2.to_board.corrupt_mask = 0x08; break;
        case 750: wire_1.to_host.drop_next = 4; break;
        case 800: wire_2.to_host.corrupt_in = 7, wire_2.to_host.corrupt_mask = 0x80; break;
        case 850: {
          const std::uint8_t garbage[] = {0xA5, 0xFF, 0x00, 0xA5, 0x02, 0x07, 0x13};
          wire_1.inject_to_board(garbage, sizeof garbage);
          break;
        }
        case 1000: hil->reset_board(1); break;
        default: break;
      }
    }
  } faults;
  faults.hil = &hil;
  const auto samples = run_pair(scene, hil, 2.5, &faults);

  for (int joint = 0; joint < 2; ++joint) CHECK(hil.link(joint).state() == LinkState::running);
  CHECK(hil.link(1).decoder().crc_errors >= 1);
  CHECK(hil.link(0).counters().seq_gaps >= 1);
  bool saw_reset = false;
  const BoardLink& reset_link = hil.link(1);
  for (std::size_t i = 0; i < reset_link.event_count(); ++i) {
    saw_reset |= reset_link.event(i).kind == LinkEventKind::board_reset;
  }
  CHECK(saw_reset);
  // The reset held the device's force on both motors, and both came back together.
  CHECK(hil.pair().held_ticks(1) > 0);
  CHECK(hil.pair().zeroed_writes() > 0);
  CHECK(hil.pair().restarts() >= 1);
  // Tick 1000's reset: within a few ticks the whole device's force is zero, not only joint 2's.
  bool zero_after_reset = false;
  for (std::size_t i = 1000; i < 1010; ++i) zero_after_reset |= norm(samples[i].output_N) == 0.0;
  CHECK(zero_after_reset);

  // The position stayed right and the box pushes again after the ramp-in: the hand
  // (1000 N/m at 4 mm in) and the wall (400 N/m) balance at 2.86 mm, 1.14 N.
  const PairSample& last = samples.back();
  CHECK(norm(last.x_m - last.x_true_m) < 0.3e-3);
  CHECK(last.output_N[0] == doctest::Approx(-1.143).epsilon(0.08));
  // No jolt, faults or not.
  CHECK(pair_largest_rise_N(samples, 600) < 0.1);
  CHECK(hil.report().find("joint 2 ") != std::string::npos);
}

TEST_CASE("hil pair: a silent link on one board zeroes both motors, and both recover together" *
          doctest::test_suite("threaded")) {
  const PlanarScene scene = load_planar_environment_text(kBoxScene, "box.json");
  const PlanarSimulationConfig simulation = held_in_box(scene);
  HilPair hil(scene.device, pair_hil_config(simulation));

  // Joint 1's board stops answering for 150 ms (its replies lost on the way to the host).
  struct Silence final : TickObserverOf<2> {
    HilPair* hil;
    std::uint64_t tick{};
    double joint_2_duty_while_silent{-1.0};
    LinkState joint_1_state_while_silent{LinkState::running};
    void on_tick(const TickStateOf<2>&) noexcept override {
      ++tick;
      if (tick >= 1000 && tick < 1150) hil->wire(0).to_host.drop_next = 1'000'000;
      if (tick == 1150) hil->wire(0).to_host.drop_next = 0;
      if (tick == 1140) {
        joint_2_duty_while_silent = hil->board(1).motor_duty();
        joint_1_state_while_silent = hil->link(0).state();
      }
    }
  } silence;
  silence.hil = &hil;
  const auto samples = run_pair(scene, hil, 2.5, &silence);

  // While joint 1's board was silent, joint 2's motor was off too (never one joint's force
  // from one fresh angle and one stale one).
  CHECK(silence.joint_1_state_while_silent == LinkState::silent);
  CHECK(silence.joint_2_duty_while_silent == 0.0);
  CHECK(norm(samples[1140].output_N) == 0.0);
  CHECK(hil.link(0).state() == LinkState::running);
  CHECK(hil.pair().restarts() >= 1);
  CHECK(samples.back().output_N[0] == doctest::Approx(-1.143).epsilon(0.08));
  CHECK(pair_largest_rise_N(samples, 600) < 0.1);
  // The silence is in joint 1's events and the summary; a silence that ends is survived,
  // not a run failure (as for one board).
  bool saw_silent = false;
  for (std::size_t i = 0; i < hil.link(0).event_count(); ++i) {
    saw_silent |= hil.link(0).event(i).kind == LinkEventKind::silent;
  }
  CHECK(saw_silent);
  CHECK(hil.report().find("joint 1 link event") != std::string::npos);
  CHECK_FALSE(hil.fault_seen());
}

TEST_CASE("hil pair: one board's process killed mid-run stops the run with zero force on both motors" *
          doctest::test_suite("threaded")) {
  const PlanarScene scene = load_planar_environment_text(kBoxScene, "box.json");
  const PlanarSimulationConfig simulation = held_in_box(scene);
  HilPair hil(scene.device, pair_hil_config(simulation));
  // Joint 2's board process dies at tick 800, while the box pushes.
  struct Killer final : TickObserverOf<2> {
    HilPair* hil;
    std::uint64_t tick{};
    double force_before_N{};
    void on_tick(const TickStateOf<2>& s) noexcept override {
      if (++tick != 800) return;
      force_before_N = norm(s.output_N);
      kill(hil->board(1).process_id(), SIGKILL);
    }
  } killer;
  killer.hil = &hil;
  ObserverListOf<2> observers;
  observers.add(&killer);
  const RunOptions options{.duration_s = 2.0, .pacing = Pacing::simulated_time};
  const RunSummaryOf<2> summary = run_scene(scene, hil, options, &observers);
  CHECK(summary.device_lost);
  CHECK(summary.ticks >= 800);
  CHECK(summary.ticks < 805);  // stopped at once, not run to 2000 ticks
  CHECK(killer.force_before_N > 0.5);
  CHECK(hil.lost());
  CHECK(hil.fault_seen());
  // Both motors off once the last command arrives: joint 2's board is gone (its pins read
  // zero) and joint 1's was sent zero.
  hil.advance(0.002);
  CHECK(hil.board(0).motor_duty() == 0.0);
  CHECK(norm(hil.motor_force_N()) == 0.0);
  const std::string report = hil.report();
  CHECK(report.find("FAULT            joint 2's board: ") != std::string::npos);
  CHECK(report.find("killed by signal 9") != std::string::npos);
}

TEST_CASE("hil pair: runs are deterministic" * doctest::test_suite("threaded")) {
  const PlanarScene scene = load_planar_environment_text(kBoxScene, "box.json");
  const PlanarSimulationConfig simulation = line_into_box(scene);
  HilPair a(scene.device, pair_hil_config(simulation));
  HilPair b(scene.device, pair_hil_config(simulation));
  CHECK(run_pair(scene, a, 0.5) == run_pair(scene, b, 0.5));
}

TEST_CASE("hil pair: a profile whose joints are not Hapkit boards is refused before any board starts") {
  const PlanarScene scene = load_planar_environment_text(R"({"device": "haplink", "effects": []})", "t.json");
  PlanarSimulationConfig simulation;
  simulation.start_q_rad = planar_joint_angles_at(scene.device, scene.device.home_m);
  CHECK_THROWS_WITH_AS(open_planar_device("hil", scene.device, simulation),
                       doctest::Contains("--device hil: profile \"haplink\" joint 1 reads an encoder"), InputError);
  const PlanarScene pantograph = load_planar_environment_text(kBoxScene, "box.json");
  CHECK_THROWS_WITH_AS(open_planar_device("hil:/nonexistent.elf", pantograph.device, simulation),
                       doctest::Contains("/nonexistent.elf"), InputError);
}

#else

TEST_CASE("hil pair: firmware-in-the-loop tests" * doctest::skip()) {
  MESSAGE("this build has no simavr or AVR toolchain");
}

#endif
