// The serial device's termios path, end to end through a pseudo-terminal: the test plays
// the board on the master side (a FakeBoard in a thread), the device opens the slave as
// it would open /dev/ttyACM0.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include "engine/devices/serial_hapkit.hpp"
#include "engine/run/runner.hpp"
#include "tests/devices/pty_board.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::PtyBoard;

namespace {

DeviceProfile hapkit3() { return test::scene_from(R"({"effects": []})").device; }

// Ticks the device in real time for `ticks` ms; returns the longest tick's read + write.
std::chrono::nanoseconds run_ticks(SerialHapkit* device, int ticks, double duty) {
  std::chrono::nanoseconds longest{0};
  for (int i = 0; i < ticks; ++i) {
    const auto begin = std::chrono::steady_clock::now();
    device->read();
    device->write(MotorCommand{duty, true});
    longest = std::max(longest, std::chrono::steady_clock::now() - begin);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return longest;
}

}  // namespace

TEST_CASE("serial: a board on a pseudo-terminal handshakes, renders, goes silent and vanishes" * doctest::test_suite("threaded")) {
  PtyBoard board;
  SerialConfig config;
  config.path = board.path();
  config.handshake_timeout_s = 2.0;
  SerialHapkit device(hapkit3(), config);
  CHECK(device.link().state() == LinkState::running);
  CHECK(device.link().identity().board_kind == HS_BOARD_HAPKIT3);

  // Normal running: the board gets the duty, the host gets the counts and a latency.
  run_ticks(&device, 100, 0.25);
  CHECK(board.commands.load() > 0);
  CHECK(board.last_duty.load() == 64);
  CHECK(device.read() == 500);
  CHECK(device.link().round_trip_ns().count() > 0);
  CHECK(device.link().round_trip_ns().percentile_ns(0.5) < 20'000'000);

  // The board goes quiet: after the silence timeout the link says so and handshakes.
  board.muted.store(true);
  run_ticks(&device, 100, 0.25);
  CHECK(device.link().state() == LinkState::silent);
  board.muted.store(false);
  run_ticks(&device, 200, 0.25);
  CHECK(device.link().state() == LinkState::running);
  CHECK(device.take_restart());

  // Unplugged: reads fail, the link is "vanished", and no tick waits for the port: a
  // blocking reopen or handshake would take its 0.5 s retry or 2 s timeout. (The bound is
  // loose on purpose: a shared machine can preempt any single tick for a few ms.)
  board.unplug();
  const auto longest = run_ticks(&device, 50, 0.25);
  CHECK(device.link().state() == LinkState::vanished);
  CHECK(longest < std::chrono::milliseconds(100));
  const std::string report = device.report();
  CHECK(report.find("silent") != std::string::npos);
  CHECK(report.find("vanished") != std::string::npos);
}

TEST_CASE("serial: a port that does not answer the handshake is an error, not a hang" * doctest::test_suite("threaded")) {
  PtyBoard board;
  board.muted.store(true);
  SerialConfig config;
  config.path = board.path();
  config.handshake_timeout_s = 0.2;
  const auto begin = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH_AS(SerialHapkit(hapkit3(), config),
                       doctest::Contains("the handshake did not complete within 0.2"), std::runtime_error);
  CHECK(std::chrono::steady_clock::now() - begin < std::chrono::seconds(1));
}

// A board reset, after which the board's count (realigned to the last position's sensor
// period) is farther from the last position than the handle can move in the time since:
// judged as every reading is, so rejected, and the loop never drives the motor on it. The
// speed bound is 1 mm/s here (82 counts/s), so that a 400-count step needs 5 s: no
// delay of this shared machine within the 0.6 s run makes it plausible. The board counts
// only the COMMANDs it takes once armed again, all sent after the host saw the reset.
TEST_CASE("serial: a reading too far from the last after a board reset gives no force" * doctest::test_suite("threaded")) {
  PtyBoard board;
  SerialConfig config;
  config.path = board.path();
  config.handshake_timeout_s = 2.0;
  config.max_handle_speed_m_per_s = 0.001;  // 82 counts/s
  const Scene scene = test::scene_from(
      R"({"effects": [{"type": "spring", "stiffness": "2000 N/m", "center": "-50 mm"}]})");
  SerialHapkit device(scene.device, config);
  struct ResetAt final : TickObserver {
    PtyBoard* board{};
    int ticks{};
    int nonzero_before{};
    void on_tick(const TickState&) noexcept override {
      if (++ticks != 200) return;
      nonzero_before = board->nonzero_commands.load();
      board->reset_to.store(900);  // 400 counts from 500
    }
  } observer;
  observer.board = &board;
  const RunOptions options{.duration_s = 0.6, .pacing = Pacing::real_time};
  (void)run_scene(scene, device, options, &observer);
  CHECK(observer.nonzero_before > 0);                // it rendered before the reset
  CHECK(device.link().events_of(LinkEventKind::board_reset) == 1);
  CHECK(device.link().events_of(LinkEventKind::connected) == 2);
  CHECK(device.link().counters().implausible_states >= 1);
  CHECK(board.nonzero_since_reset.load() == 0);      // and never after it
  CHECK(device.fault_seen());
  CHECK(device.report().find("implausible") != std::string::npos);
}
