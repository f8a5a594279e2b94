// `hapscene calibrate` end to end on the firmware-in-the-loop board: the simulated hand
// plays the user (centre, end to end, let go) and the written profile extends the shipped
// one with only what the measurement changed.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/devices/profile.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/devices/pty_board.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;
using namespace hapscene::test;

#if HAPSCENE_HAVE_HIL
TEST_CASE("calibrate: on hil, a kit that differs gets a profile overriding what differs" * doctest::test_suite("threaded")) {
  ScratchFolder folder("calibrate_hil");
  // The kit on the desk: the sensor magnet turned by about a degree, the motor wired the
  // other way round, and a shorter travel than the shipped profile's.
  const std::string kit = (folder.dir / "odd_kit.json").string();
  std::ofstream(kit) << R"({"extends": "hapkit3", "name": "odd kit",
    "sensor": {"counts_to_deg_offset": 6.0}, "drive": {"direction_sign": -1},
    "plant": {"end_stops": ["-50 mm", "40 mm"]}})";
  const std::string output = (folder.dir / "mine.json").string();
  const CliOutcome outcome = run_cli("calibrate --device hil --simulated-kit " + kit + " --yes --travel-time 2.5s --output " + output);
  CAPTURE(outcome.out);
  CAPTURE(outcome.err);
  REQUIRE(outcome.exit_code == 0);
  CHECK(outcome.out.find("  centre reads 561.0 counts: -1.2 mm with hapkit3's offset\n") != std::string::npos);
  CHECK(outcome.out.find(" sensor periods unwrapped), -50.1 mm to 40.1 mm (90.1 mm)\n") != std::string::npos);
  CHECK(outcome.out.find("the handle moves against the force: direction_sign -1") != std::string::npos);
  CHECK(outcome.out.find("overrides sensor.counts_to_deg_offset 6.0027, drive.direction_sign -1, limits.workspace "
                         "[-47.0 mm, 37.0 mm]") != std::string::npos);

  // The file extends the shipped profile and overrides only those keys.
  const std::string text = slurp_file(output);
  CHECK(text.find("\"extends\": \"hapkit3\"") != std::string::npos);
  CHECK(text.find("pulley_radius") == std::string::npos);
  const DeviceProfile mine = load_device_profile(output, ".");
  const DeviceProfile shipped = load_device_profile("hapkit3", ".");
  CHECK(mine.drive.direction_sign == -1);
  CHECK(mine.sensor.counts_to_deg_offset == doctest::Approx(6.0).epsilon(0.001));
  CHECK(mine.limits.workspace_min_m == doctest::Approx(-0.047));
  CHECK(mine.limits.workspace_max_m == doctest::Approx(0.037));
  CHECK(mine.plant.mass_kg == shipped.plant.mass_kg);
  CHECK(mine.drive.motor_constant_N_m == shipped.drive.motor_constant_N_m);
}

TEST_CASE("calibrate: on hil, the shipped profile fits the shipped kit" * doctest::test_suite("threaded")) {
  ScratchFolder folder("calibrate_fits");
  const std::string output = (folder.dir / "same.json").string();
  const CliOutcome outcome = run_cli("calibrate --device hil --yes --travel-time 2.5s --output " + output);
  CAPTURE(outcome.out);
  REQUIRE(outcome.exit_code == 0);
  CHECK(outcome.out.find("the handle moves with the force: direction_sign 1") != std::string::npos);
  CHECK(outcome.out.find("nothing differs (the shipped profile fits this kit)") != std::string::npos);
  CHECK(load_device_profile(output, ".").limits.workspace_min_m == doctest::Approx(-0.050));
}
#endif

TEST_CASE("calibrate: refusals" * doctest::test_suite("threaded")) {
  ScratchFolder folder("calibrate_refusals");
  // A simulated kit only stands in for simulated devices; a pulse stays small.
  CHECK(run_cli("calibrate --device serial:/dev/null --simulated-kit hapkit3").exit_code == 2);
  CHECK(run_cli("calibrate --device sim --pulse-force 3N").exit_code == 2);
  // A pulse above a profile file's force limit: the file and its key are named.
  const std::string weak = (folder.dir / "weak.json").string();
  std::ofstream(weak) << R"({"extends": "hapkit3", "name": "weak", "limits": {"max_force": "0.3 N"}})";
  const CliOutcome too_strong = run_cli("calibrate --device sim --profile " + weak + " --pulse-force 0.5N");
  CHECK(too_strong.exit_code == 2);
  CHECK(too_strong.err.find(weak + " (extends hapkit3): /limits/max_force") != std::string::npos);
  CHECK(run_cli("calibrate --device sim --profile hapkit33").err.find("did you mean \"hapkit3\"") != std::string::npos);
  // A handle that never moves: nothing is written, exit 1. (A kit whose end stops leave
  // 10 mm of travel.)
  const std::string kit = (folder.dir / "stuck.json").string();
  std::ofstream(kit) << R"({"extends": "hapkit3", "name": "stuck", "plant": {"end_stops": ["-5 mm", "5 mm"]}})";
  const std::string output = (folder.dir / "never.json").string();
  const CliOutcome stuck = run_cli("calibrate --device sim --simulated-kit " + kit + " --yes --output " + output);
  CHECK(stuck.exit_code == 1);
  CHECK(stuck.out.find("FAIL the handle moved only ") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(output));
}

// A board on a serial port that answers the handshake and then stops answering is named as
// that, not measured as a handle that moved 0.0 mm: in the centre step (silent from its
// first COMMAND on) and in the travel step (silent after the 1000 COMMANDs of the centre
// step and 200 more). The steps count ticks, so where the silence falls does not depend
// on this machine's speed.
TEST_CASE("calibrate: a board that stops answering is not a handle that did not move" * doctest::test_suite("threaded")) {
  ScratchFolder folder("calibrate_silent");
  const struct {
    int mute_after;
    const char* step;
  } cases[] = {{0, "centre"}, {1200, "travel"}};
  for (const auto& c : cases) {
    CAPTURE(c.step);
    PtyBoard board;
    board.mute_after_commands.store(c.mute_after);
    const std::string output = (folder.dir / "never.json").string();
    const CliOutcome out =
        run_cli("calibrate --device serial:" + board.path() + " --yes --travel-time 1s --output " + output);
    CAPTURE(out.out);
    CAPTURE(out.err);
    CHECK(out.exit_code == 1);
    CHECK(out.out.find(std::string("FAIL the board stopped answering after the handshake (no reading for ")) !=
          std::string::npos);
    CHECK(out.out.find(std::string(" ms in the ") + c.step + " step, its link ") != std::string::npos);
    CHECK(out.out.find("the handle moved only") == std::string::npos);
    CHECK_FALSE(std::filesystem::exists(output));
  }
}
