// The Haply device end to end through a pseudo-terminal: the test plays a board running
// the stock firmware on the master side (a FakeHaplyBoard in a thread); the device opens
// the slave as it would open /dev/ttyACM0. Every way a run can end leaves zero torque on
// the board: a clean close here, and through the watchdog process a kill -9 and a stalled
// process (SIGSTOP) of a forked host.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <thread>
#include <vector>

#include "engine/devices/haply/haply_device.hpp"
#include "tests/devices/pty_haply_board.hpp"

using namespace hapscene;
using hapscene::test::PtyHaplyBoard;

namespace {

PlanarProfile v3() { return load_planar_profile("haply2diy_v3", "."); }

HaplyConfig config_for(const std::string& path) {
  HaplyConfig config;
  config.path = path;
  config.handshake_timeout_s = 2.0;
  config.watchdog_stall_ns = 100'000'000;
  return config;
}

PlanarMotorCommand torque_command(double t1_N_m, double t2_N_m) {
  PlanarMotorCommand command;
  command.torque_N_m = Vec2{{t1_N_m, t2_N_m}};
  return command;
}

bool torque_on(const test::FakeHaplyBoard& b) { return b.torque_N_m[0] != 0.0f || b.torque_N_m[1] != 0.0f; }
bool torque_off(const test::FakeHaplyBoard& b) { return b.torque_N_m[0] == 0.0f && b.torque_N_m[1] == 0.0f; }

// A forked host: opens the device and ticks at about 1 kHz with a torque, forever; after a
// restart (the watchdog fired while it was stopped) it commands a different torque, so the
// test can see it noticed.
[[noreturn]] void host_process(const std::string& path) {
  try {
    HaplyDevice device(v3(), config_for(path));
    double torque_N_m = 0.05;
    for (;;) {
      (void)device.read();
      if (device.take_restart()) torque_N_m = 0.07;
      device.write(torque_command(torque_N_m, -torque_N_m));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  } catch (...) {
    _exit(3);
  }
}

bool process_gone(pid_t pid) { return kill(pid, 0) != 0; }

}  // namespace

TEST_SUITE("threaded") {
TEST_CASE("haply device: opens on a serial port, renders, and leaves zero torque when closed") {
  PtyHaplyBoard board;
  pid_t watchdog = -1;
  {
    HaplyDevice device(v3(), config_for(board.path()));
    watchdog = device.watchdog_pid();
    CHECK(watchdog > 0);
    // One setup, or more when a late byte made the link run it again (a setup retry).
    CHECK(board.with_board([](auto& b) { return b.setups; }) ==
          1 + static_cast<int>(device.link().counters().setup_retries));
    for (int i = 0; i < 50; ++i) {
      const PlanarReading reading = device.read();
      CHECK(std::fabs(reading.angle_deg[0] - 168.0) <= 360.0 / 4880.0);  // one count
      device.write(torque_command(0.04, 0.02));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    CHECK(board.wait_for([](auto& b) { return b.torque_N_m[1] == 0.04f; }, 500));
    CAPTURE(device.report());
    // Fresh again within a few ticks (a loaded machine can delay one reply past 5 ms).
    for (int i = 0; i < 200 && device.position_status() != PositionStatus::fresh; ++i) {
      (void)device.read();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    CHECK(device.position_status() == PositionStatus::fresh);
    // No fault, unless this shared machine starved the fake board's thread for 50 ms (a
    // silent board to the link, which then says so).
    if (device.fault_seen()) {
      CHECK(device.report().find("resyncs (silence ") != std::string::npos);
    } else {
      CHECK(device.report().find("; 0 resyncs;") != std::string::npos);
    }
  }
  CHECK(board.wait_for(torque_off, 500));
  // A clean end: the watchdog was told, exited and was reaped.
  CHECK(process_gone(watchdog));
}

TEST_CASE("haply device: a board that never answers is an error after the handshake timeout") {
  PtyHaplyBoard board;
  board.with_board([](auto& b) { return b.muted = true; });
  HaplyConfig config = config_for(board.path());
  config.handshake_timeout_s = 0.2;
  CHECK_THROWS_WITH_AS(HaplyDevice(v3(), config), doctest::Contains("no reply to the setup within 0.2 s"),
                       std::runtime_error);
  // It said hello (reset and setup) and asked again on silence, with no torque ever.
  CHECK(board.with_board([](auto& b) { return b.setups; }) >= 1);
  CHECK(board.with_board(torque_off));
}

TEST_CASE("haply device: the watchdog zeroes the torque when the host is killed (kill -9)") {
  PtyHaplyBoard board;
  const pid_t host = fork();
  REQUIRE(host >= 0);
  if (host == 0) host_process(board.path());
  const bool rendering = board.wait_for(torque_on, 5000);
  CHECK(rendering);
  kill(host, SIGKILL);
  int status = 0;
  waitpid(host, &status, 0);
  CHECK(WIFSIGNALED(status));
  // The board keeps the last torque on its own: only the watchdog can take it off.
  CHECK(board.wait_for(torque_off, 2000));
}

TEST_CASE("haply device: the watchdog zeroes the torque of a stalled host, which then ramps in again") {
  PtyHaplyBoard board;
  const pid_t host = fork();
  REQUIRE(host >= 0);
  if (host == 0) host_process(board.path());
  CHECK(board.wait_for([](auto& b) { return b.torque_N_m[1] == 0.05f; }, 5000));
  kill(host, SIGSTOP);
  CHECK(board.wait_for(torque_off, 2000));   // the stall bound is 100 ms
  kill(host, SIGCONT);
  // The host saw the watchdog had fired (a restart) and renders again.
  CHECK(board.wait_for([](auto& b) { return b.torque_N_m[1] == 0.07f; }, 2000));
  kill(host, SIGKILL);
  waitpid(host, nullptr, 0);
  CHECK(board.wait_for(torque_off, 2000));
}
}
