// Firmware-in-the-loop with the simulated board in its own process (hapscene-board): a
// board process that dies or hangs in the middle of a run is a clean device fault (zero
// force, the run stops, the report says what happened), never a crash of hapscene.
#include <doctest/doctest.h>

#include <signal.h>

#include <cstdlib>
#include <string>

#include "engine/devices/open_device.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/support.hpp"

#if HAPSCENE_HAVE_HIL
#include "engine/devices/hil/hil_hapkit.hpp"
#include "engine/run/runner.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

HilConfig hil_config() {
  HilConfig config;
  config.firmware_elf = default_firmware_elf();
  return config;
}

// Sends `signal_number` to the board process at tick `at_tick`, and keeps the motor force
// the plant felt after every tick.
class SignalBoardAt final : public TickObserver {
 public:
  SignalBoardAt(const HilHapkit& hil, std::uint64_t at_tick, int signal_number)
      : hil_(hil), at_tick_(at_tick), signal_(signal_number) {}
  void on_tick(const TickState& s) noexcept override {
    if (s.tick == at_tick_) kill(hil_.board().process_id(), signal_);
    last_motor_force_N = hil_.motor_force_N();
  }
  double last_motor_force_N{-1.0};

 private:
  const HilHapkit& hil_;
  std::uint64_t at_tick_;
  int signal_;
};

}  // namespace

TEST_CASE("hil board process: killed mid-run, the run stops with zero force and says why" *
          doctest::test_suite("threaded")) {
  // A spring holding the handle away from the centre: force is on when the board dies.
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 300, "center": "10 mm"}]})");
  HilHapkit hil(scene.device, hil_config());
  SignalBoardAt killer(hil, 300, SIGKILL);
  const RunOptions options{.duration_s = 2.0, .pacing = Pacing::simulated_time};
  const RunSummary summary = run_scene(scene, hil, options, &killer);
  CHECK(summary.device_lost);
  CHECK(summary.ticks >= 300);
  CHECK(summary.ticks < 305);  // stopped at once (in the tick's advance), not run to 2000 ticks
  CHECK(hil.lost());
  CHECK(hil.fault_seen());
  CHECK(killer.last_motor_force_N != 0.0);  // the spring was pushing when the board died
  CHECK(hil.motor_force_N() == 0.0);        // and the plant felt no motor force after
  const std::string report = hil.report();
  MESSAGE(report);
  CHECK(report.find("FAULT") != std::string::npos);
  CHECK(report.find("killed by signal 9") != std::string::npos);
  CHECK(report.find("zero force commanded, run stopped") != std::string::npos);
}

TEST_CASE("hil board process: a hung board is killed after the reply timeout and the run stops" *
          doctest::test_suite("threaded")) {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 300}]})");
  HilHapkit hil(scene.device, hil_config());
  const pid_t board = hil.board().process_id();
  SignalBoardAt stopper(hil, 100, SIGSTOP);  // the process stops answering
  const RunOptions options{.duration_s = 1.0, .pacing = Pacing::simulated_time};
  const RunSummary summary = run_scene(scene, hil, options, &stopper);
  CHECK(summary.device_lost);
  CHECK(summary.ticks < 110);
  CHECK(hil.motor_force_N() == 0.0);
  CHECK(hil.report().find("did not answer within 5 s (killed)") != std::string::npos);
  CHECK(kill(board, 0) != 0);  // gone, and reaped
}

TEST_CASE("hil board process: a board that aborts mid-run is exit 1 with the reason on the command line" *
          doctest::test_suite("threaded")) {
  // The board process's test hook: abort when the board reaches 0.5 s of its life.
  setenv("HAPSCENE_BOARD_ABORT_AT_CYCLE", "8000000", 1);
  const test::CliOutcome outcome = test::run_cli("run environments/spring.json --device hil --sim-time --duration 2s");
  unsetenv("HAPSCENE_BOARD_ABORT_AT_CYCLE");
  INFO(outcome.out << outcome.err);
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.out.find("was killed by signal 6 (Aborted)") != std::string::npos);
  CHECK(outcome.out.find("zero force commanded, run stopped") != std::string::npos);
}

TEST_CASE("hil board process: the abort hook is read whole, never as another cycle" *
          doctest::test_suite("threaded")) {
  // "8000000x" once read as 8000000 (strtoull); now the board refuses it before the run.
  setenv("HAPSCENE_BOARD_ABORT_AT_CYCLE", "8000000x", 1);
  const test::CliOutcome outcome = test::run_cli("run environments/spring.json --device hil --sim-time --duration 2s");
  unsetenv("HAPSCENE_BOARD_ABORT_AT_CYCLE");
  INFO(outcome.out << outcome.err);
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.err.find("HAPSCENE_BOARD_ABORT_AT_CYCLE: expected a whole number of cycles, got \"8000000x\"") !=
        std::string::npos);
  CHECK(outcome.out.find("was killed by signal 6") == std::string::npos);
}

TEST_CASE("hil board process: the board process ends with the device") {
  pid_t board = -1;
  {
    const Scene scene = scene_from(R"({"effects": []})");
    HilHapkit hil(scene.device, hil_config());
    board = hil.board().process_id();
    CHECK(kill(board, 0) == 0);
  }
  CHECK(kill(board, 0) != 0);  // ended and reaped, no zombie left
}

#else
TEST_CASE("hil board process: needs simavr and the AVR toolchain" * doctest::skip()) {}
#endif
