// The Haply device end to end through a pseudo-terminal: the test plays a board running
// the stock firmware on the master side (a FakeHaplyBoard in a thread); the device opens
// the slave as it would open /dev/ttyACM0. A clean close leaves zero torque on the board
// (a kill -9 and a stalled host, which the watchdog process covers, are tested on a real
// hapscene process: tests/cli/haply_run_cli_test.cpp).
#include <doctest/doctest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

#include "engine/devices/haply/haply_device.hpp"
#include "tests/devices/pty_haply_board.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

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

bool torque_off(const test::FakeHaplyBoard& b) { return b.torque_N_m[0] == 0.0f && b.torque_N_m[1] == 0.0f; }

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

// On a serial port, a board that answers a resync with angles no arm can have: 3e17 deg, a
// NaN, a jump farther from the preset offsets than the arm turns (a speed bound of 0.5
// rad/s here, so that no delay of this shared machine can make the jump possible). Not
// one torque frame with a torque reaches the board after the resync's reset (the port
// keeps the order: frames sent before the reset arrive before it), the rejections are
// counted and reported, and the run would fail.
TEST_CASE("haply device: implausible angles after a resync never give a torque frame") {
  struct Bad {
    const char* name;
    float deg;
    const char* said;
  };
  const Bad bads[] = {{"3e17 deg", 3e17f, "outside the sensor's range"},
                      {"NaN", std::numeric_limits<float>::quiet_NaN(), "not a finite number"},
                      {"a jump", 100.0f, "farther than the device can move"}};
  for (const Bad& bad : bads) {
    CAPTURE(std::string(bad.name));
    PtyHaplyBoard board;
    HaplyConfig config = config_for(board.path());
    config.link.max_joint_speed_rad_per_s = 0.5;
    config.watchdog = false;
    HaplyDevice device(v3(), config);
    for (int i = 0; i < 20; ++i) {
      (void)device.read();
      device.write(torque_command(0.04, 0.02));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    REQUIRE(board.wait_for([](auto& b) { return b.torque_since_reset > 0; }, 500));
    // The next reply has a wrong id (a resync), and every one after it the bad angles.
    board.with_board([&](auto& b) {
      b.wrong_ids = 1;
      b.forced_replies = 1'000'000;
      b.forced_deg = bad.deg;
      return 0;
    });
    // Ticks until the board has seen the resync's reset and two setups after it.
    const int resets_before = board.with_board([](auto& b) { return b.resets; });
    int ticks = 0;
    for (; ticks < 2000 && board.with_board([](auto& b) { return b.resets; }) < resets_before + 3; ++ticks) {
      (void)device.read();
      device.write(torque_command(0.04, 0.02));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    REQUIRE(ticks < 2000);
    CHECK(board.with_board([](auto& b) { return b.torque_since_reset; }) == 0);
    CHECK(device.link().counters().implausible >= 1);
    CHECK(device.fault_seen());
    CHECK(device.report().find(bad.said) != std::string::npos);
    DeviceLinkHealth health;
    device.link_health(&health);
    CHECK(health.link[0].implausible == device.link().counters().implausible);
  }
}

TEST_CASE("haply device: a board that answers the setup only with implausible angles is not opened") {
  PtyHaplyBoard board;
  board.with_board([](auto& b) {
    b.forced_replies = 1'000'000;
    b.forced_deg = 3e17f;
    return 0;
  });
  HaplyConfig config = config_for(board.path());
  config.handshake_timeout_s = 0.2;
  config.watchdog = false;
  CHECK_THROWS_WITH_AS(HaplyDevice(v3(), config), doctest::Contains("no plausible reply to the setup within 0.2 s"),
                       std::runtime_error);
  CHECK(board.with_board([](auto& b) { return b.torque_since_reset; }) == 0);
}
}

}  // namespace HAPSCENE_TEST_FILE
