// Two Hapkit boards as one 2-DOF device (`--device serial:A,B`), each a FakeBoard on its
// own pseudo-terminal: the device reads both joints and commands both motors; a fault on
// either board zeroes both motors, the report names the board, and both ramp in together.
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <thread>

#include "engine/base/errors.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/devices/planar/hapkit_pair.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "tests/devices/pty_board.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;
using hapscene::test::PtyBoard;

namespace {

std::size_t test_occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

PlanarProfile pantograph() { return load_planar_profile("hapkit_pantograph", "."); }

HapkitPairConfig pair_config(const PtyBoard& first, const PtyBoard& second) {
  HapkitPairConfig config;
  config.paths = {first.path(), second.path()};
  config.handshake_timeout_s = 2.0;
  return config;
}

// Joint 1 a quarter duty, joint 2 half: each board must get its own.
PlanarMotorCommand both_motors() {
  PlanarMotorCommand command;
  command.motor[0] = MotorCommand{0.25, true};
  command.motor[1] = MotorCommand{0.5, false};
  return command;
}

// Ticks in real time (1 ms) until `done` or `max_ticks`; true when `done` came. Each tick
// is the loop's: read, take_restart, write. `restarted` is set when take_restart fired.
bool tick_until(HapkitPair* device, int max_ticks, const std::function<bool()>& done, bool* restarted = nullptr) {
  for (int i = 0; i < max_ticks; ++i) {
    device->read();
    if (device->take_restart() && restarted != nullptr) *restarted = true;
    device->write(both_motors());
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

void tick(HapkitPair* device, int ticks) { tick_until(device, ticks, [] { return false; }); }

// Both boards render: joint 1's board gets 64/255, joint 2's about 128/255.
void check_both_render(HapkitPair* device, PtyBoard& first, PtyBoard& second) {
  CHECK(tick_until(device, 500, [&] {
    return device->position_status() == PositionStatus::fresh && first.last_duty.load() == 64 &&
           second.last_duty.load() >= 127;
  }));
}

// A fault on joint 2's board (made by `start`, ended by `stop`): both motors get zero while
// it lasts, the report names joint 2, and both ramp in together when it is over.
void check_fault_on_joint_2(const std::function<void(PtyBoard&)>& start, const std::function<void(PtyBoard&)>& stop,
                            const char* event, bool lasting = true) {
  PtyBoard first, second;
  HapkitPair device(pantograph(), pair_config(first, second));
  check_both_render(&device, first, second);

  // A fault that does not last (a reset) is over at once: both links may be running again,
  // and the restart taken, while the ticks below still check the fault, so they watch
  // for it too (a tick loop that dropped it made the wait for it below time out).
  bool restarted = false;
  bool* restart_seen = lasting ? nullptr : &restarted;
  start(second);
  REQUIRE(tick_until(&device, 1000, [&] { return device.position_status() != PositionStatus::fresh; }, restart_seen));
  // The healthy board's motor gets zero too (and, for a fault that lasts, stays there).
  CHECK(tick_until(&device, 200, [&] { return first.zero_commands.load() > 0; }, restart_seen));
  if (lasting) {
    tick(&device, 20);
    CHECK(first.last_duty.load() == 0);
  }
  CHECK(device.pair().zeroed_writes() > 0);
  CHECK(device.pair().held_ticks(1) > 0);
  // The report names the board (the event may come a little after the hold: silence is
  // declared after 50 ms, a stale position after 5).
  const std::string joint_2_event = std::string(" s: ") + event;
  CHECK(tick_until(&device, 500, [&] { return device.report().find(joint_2_event) != std::string::npos; },
                   restart_seen));
  const std::string report = device.report();
  const std::size_t at = report.find(joint_2_event);
  REQUIRE(at != std::string::npos);
  CHECK(report.rfind("\n", at) == report.rfind("\n  joint 2 link event       ", at));
  CHECK(report.find("  joint 2 port     " + second.path()) != std::string::npos);

  // Over: both links running, one restart for both, then both boards render again.
  stop(second);
  CHECK(tick_until(&device, 2000, [&] { return restarted; }, &restarted));
  CHECK(device.link(0).state() == LinkState::running);
  CHECK(device.link(1).state() == LinkState::running);
  check_both_render(&device, first, second);
}

}  // namespace

TEST_SUITE("threaded") {
TEST_CASE("hapkit pair: two boards read as joints 1 and 2 and each motor gets its own command") {
  PtyBoard first, second;
  first.counts.store(480);
  second.counts.store(530);
  HapkitPair device(pantograph(), pair_config(first, second));
  CHECK(device.link(0).state() == LinkState::running);
  CHECK(device.link(1).state() == LinkState::running);
  CHECK_FALSE(device.take_restart());  // the first contact is the run's own soft start
  check_both_render(&device, first, second);
  const PlanarReading reading = device.read();
  CHECK(reading.counts[0] == 480);
  CHECK(reading.counts[1] == 530);
  CHECK(first.last_duty.load() == 64);
  CHECK((second.last_duty.load() == 127 || second.last_duty.load() == 128));
  CHECK_FALSE(device.fault_seen());
  const std::string report = device.report();
  CHECK(report.find("  joint 1 port     " + first.path()) != std::string::npos);
  CHECK(report.find("  joint 2 port     " + second.path()) != std::string::npos);
  CHECK(report.find("  joint 1 board            hapkit firmware") != std::string::npos);
  CHECK(report.find("  joint 2 round trip       p50") != std::string::npos);
  CHECK(report.find("  two boards       ") != std::string::npos);
}

TEST_CASE("hapkit pair: a board gone silent zeroes both motors, and both ramp in when it answers") {
  check_fault_on_joint_2([](PtyBoard& b) { b.muted.store(true); }, [](PtyBoard& b) { b.muted.store(false); },
                         "silent (no reply)");
}

TEST_CASE("hapkit pair: a board that resets zeroes both motors until it is armed again") {
  // The board resets (its motor off, disarmed) and stays mute while it boots.
  check_fault_on_joint_2(
      [](PtyBoard& b) {
        b.reset_to.store(510);
        b.counts.store(510);
      },
      [](PtyBoard&) {}, "board was reset", false);
}

TEST_CASE("hapkit pair: corrupt data from a board zeroes both motors, and both come back together") {
  check_fault_on_joint_2([](PtyBoard& b) { b.corrupt.store(true); }, [](PtyBoard& b) { b.corrupt.store(false); },
                         "silent (no reply)");
}

TEST_CASE("hapkit pair: a board alive but sending no position (stale) zeroes both motors") {
  check_fault_on_joint_2([](PtyBoard& b) { b.states_muted.store(true); },
                         [](PtyBoard& b) { b.states_muted.store(false); }, "position stale");
}

TEST_CASE("hapkit pair: an implausible position on one board zeroes both motors and fails the run") {
  PtyBoard first, second;
  HapkitPair device(pantograph(), pair_config(first, second));
  check_both_render(&device, first, second);
  first.counts.store(500 + 40000);  // a jump no hand makes in a millisecond
  REQUIRE(tick_until(&device, 500, [&] { return device.position_status() == PositionStatus::implausible; }));
  CHECK(tick_until(&device, 200, [&] { return second.last_duty.load() == 0; }));
  CHECK(device.fault_seen());
  CHECK(device.pair().held_ticks(0) > 0);
  CHECK(device.report().find("joint 1 link event") != std::string::npos);
  first.counts.store(500);
  check_both_render(&device, first, second);
}

TEST_CASE("hapkit pair: an unplugged board zeroes both motors and no tick waits for it") {
  PtyBoard first, second;
  HapkitPair device(pantograph(), pair_config(first, second));
  check_both_render(&device, first, second);
  first.unplug();
  const auto begin = std::chrono::steady_clock::now();
  REQUIRE(tick_until(&device, 500, [&] { return device.link(0).state() == LinkState::vanished; }));
  tick(&device, 20);
  CHECK(second.last_duty.load() == 0);
  CHECK(device.position_status() != PositionStatus::fresh);
  CHECK(std::chrono::steady_clock::now() - begin < std::chrono::seconds(2));
  const std::string report = device.report();
  CHECK(report.find("  joint 1 link event       ") != std::string::npos);
  CHECK(report.find("vanished") != std::string::npos);
  CHECK(report.find("  joint 2 link event       0.") != std::string::npos);  // connected
  CHECK(test_occurrences(report, "  joint 2 link event") == 1);           // and nothing more
}

TEST_CASE("hapkit pair: a board that does not answer is named in the error, after both were tried at once") {
  PtyBoard first, second;
  second.muted.store(true);
  HapkitPairConfig config = pair_config(first, second);
  config.handshake_timeout_s = 0.2;
  const auto begin = std::chrono::steady_clock::now();
  const std::string expected = "joint 2's board " + second.path() + ": the handshake did not complete";
  CHECK_THROWS_WITH_AS(HapkitPair(pantograph(), config), doctest::Contains(expected.c_str()), std::runtime_error);
  CHECK(std::chrono::steady_clock::now() - begin < std::chrono::seconds(1));
}

TEST_CASE("hapkit pair: one device named twice is refused before any port opens") {
  PtyBoard board;
  HapkitPairConfig config;
  config.paths = {board.path(), board.path()};
  CHECK_THROWS_WITH_AS(HapkitPair(pantograph(), config), doctest::Contains("both paths name the same device"),
                       InputError);
  // A symlink to the same port is the same device.
  const test::ScratchFolder folder("hapkit_pair_same");
  const std::filesystem::path link = folder.dir / "ttyLINK";
  std::filesystem::create_symlink(board.path(), link);
  config.paths = {board.path(), link.string()};
  CHECK_THROWS_WITH_AS(HapkitPair(pantograph(), config), doctest::Contains("both paths name the same device"),
                       InputError);
  CHECK(board.hellos.load() == 0);
}
}  // TEST_SUITE

TEST_CASE("hapkit pair: the device string takes exactly two paths, and only Hapkit-style joints") {
  const PlanarSimulationConfig simulation;
  CHECK_THROWS_WITH_AS(open_planar_device("serial:/dev/null", pantograph(), simulation),
                       doctest::Contains("one port for a 2-DOF scene"), InputError);
  CHECK_THROWS_WITH_AS(open_planar_device("serial:/a,/b,/c", pantograph(), simulation),
                       doctest::Contains("more than two ports"), InputError);
  CHECK_THROWS_WITH_AS(open_planar_device("serial:/a,", pantograph(), simulation),
                       doctest::Contains("an empty port path"), InputError);
  CHECK_THROWS_WITH_AS(open_planar_device("serial", pantograph(), simulation),
                       doctest::Contains("one port for a 2-DOF scene"), InputError);
  CHECK_THROWS_WITH_AS(open_planar_device("serial:/a,/b", load_planar_profile("haply2diy_v3", "."), simulation),
                       doctest::Contains("joint 1 is not a Hapkit board"), InputError);
  // serial:A,B on a 1-DOF scene
  const DeviceProfile hapkit3 = load_device_profile("hapkit3", ".");
  CHECK_THROWS_WITH_AS(open_device("serial:/a,/b", hapkit3, SimulationConfig{}),
                       doctest::Contains("is 1-DOF and takes one port"), InputError);
}
