// `hapscene run PLANAR --device serial:A,B` end to end: a hapscene process drives two fake
// Hapkit boards on two pseudo-terminals as joints 1 and 2 of a 2-DOF scene, and the run
// summary shows both links; malformed device strings are usage errors (exit 2).
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/devices/pty_board.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;
using namespace hapscene::test;

namespace {

// A box in a Hapkit pantograph's workspace (two Hapkit boards, MR sensors: what the
// hapscene firmware drives), written to a scratch folder; returns its path. At 100 Hz: these
// tests are about the device path, not a loaded machine's ability to keep 1 kHz.
std::string pantograph_scene(const ScratchFolder& folder) {
  return folder
      .write("pantograph_box.json",
             R"({"name": "pantograph_box", "device": "hapkit_pantograph", "rate_hz": 100, "effects": [{"type": "box",
                "min": ["40 mm", "140 mm"], "max": ["60 mm", "150 mm"], "stiffness": "200 N/m", "solid": "inside"}]})")
      .string();
}

}  // namespace

TEST_SUITE("threaded") {
TEST_CASE("hapkit pair cli: a 2-DOF run on two boards exits 0 and shows both links") {
  const ScratchFolder folder("hapkit_pair_cli_run");
  PtyBoard first, second;
  const CliOutcome out = run_cli("run '" + pantograph_scene(folder) + "' --device serial:" + first.path() +
                                 "," + second.path() + " --duration 0.5s --no-reload --quiet");
  CHECK(out.exit_code == 0);
  CHECK(out.out.find("  joint 1 port     " + first.path()) != std::string::npos);
  CHECK(out.out.find("  joint 2 port     " + second.path()) != std::string::npos);
  CHECK(out.out.find("  joint 1 board            hapkit firmware") != std::string::npos);
  CHECK(out.out.find("  joint 2 board            hapkit firmware") != std::string::npos);
  CHECK(out.out.find("  joint 1 link             ") != std::string::npos);
  CHECK(out.out.find("  joint 2 round trip       ") != std::string::npos);
  CHECK(out.out.find("  two boards       ") != std::string::npos);
  CHECK(first.commands.load() > 40);  // 0.5 s at 100 Hz
  CHECK(second.commands.load() > 40);
  CHECK(first.last_duty.load() == 0);  // zero on the way out
  CHECK(second.last_duty.load() == 0);
}

TEST_CASE("hapkit pair cli: --baud reaches both boards' ports") {
  const ScratchFolder folder("hapkit_pair_cli_baud");
  const std::string scene = pantograph_scene(folder);
  PtyBoard first, second;
  const CliOutcome out = run_cli("run '" + scene + "' --device serial:" + first.path() +
                                 "," + second.path() + " --baud 115200 --duration 0.1s --no-reload --quiet");
  CHECK(out.exit_code == 0);
  const CliOutcome bad = run_cli("run '" + scene + "' --device serial:" + first.path() +
                                 "," + second.path() + " --baud 12345 --duration 0.1s --no-reload --quiet");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("baud") != std::string::npos);
}

TEST_CASE("hapkit pair cli: a board that never answers fails the run (exit 1) and is named") {
  const ScratchFolder folder("hapkit_pair_cli_mute");
  const std::string scene = pantograph_scene(folder);
  PtyBoard first, second;
  second.muted.store(true);
  const CliOutcome out = run_cli("run '" + scene + "' --device serial:" + first.path() +
                                 "," + second.path() + " --duration 0.1s --no-reload --quiet");
  CHECK(out.exit_code == 1);
  CHECK(out.err.find("joint 2's board " + second.path()) != std::string::npos);
}

TEST_CASE("hapkit pair cli: malformed or mismatched device strings are usage errors") {
  PtyBoard board;
  const ScratchFolder folder("hapkit_pair_cli_errors");
  const std::string planar = "run '" + pantograph_scene(folder) + "' --duration 0.1s --no-reload --device ";
  const CliOutcome one = run_cli(planar + "serial:" + board.path());
  CHECK(one.exit_code == 2);
  CHECK(one.err.find("one port for a 2-DOF scene") != std::string::npos);
  const CliOutcome twice = run_cli(planar + "serial:" + board.path() + "," + board.path());
  CHECK(twice.exit_code == 2);
  CHECK(twice.err.find("both paths name the same device") != std::string::npos);
  const CliOutcome missing = run_cli(planar + "serial:" + board.path() + ",/dev/hapscene-no-such-port");
  CHECK(missing.exit_code == 2);
  CHECK(missing.err.find("/dev/hapscene-no-such-port") != std::string::npos);
  const CliOutcome haply = run_cli("run environments/planar/haply2diy_v3_box_inside.json --duration 0.1s "
                                   "--no-reload --device serial:/a,/b");
  CHECK(haply.exit_code == 2);
  CHECK(haply.err.find("is not a Hapkit board") != std::string::npos);
  // The Haplink's joints read encoders, which the hapscene firmware does not.
  const CliOutcome haplink = run_cli("run environments/planar/haplink_box_inside.json --duration 0.1s "
                                     "--no-reload --device serial:/a,/b");
  CHECK(haplink.exit_code == 2);
  CHECK(haplink.err.find("joint 1 reads an encoder, but the hapscene firmware reads the Hapkit's MR sensor") !=
        std::string::npos);
  const CliOutcome one_dof = run_cli("run environments/wall.json --duration 0.1s --device serial:/a,/b");
  CHECK(one_dof.exit_code == 2);
  CHECK(one_dof.err.find("is 1-DOF and takes one port") != std::string::npos);
  CHECK(board.hellos.load() == 0);
}
}  // TEST_SUITE
