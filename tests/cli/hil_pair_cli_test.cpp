// `hapscene run PLANAR --device hil` end to end: two simulated boards running the firmware
// as the joints of a Hapkit pantograph; the run summary shows both links; a profile whose
// joints the firmware cannot drive is a usage error (exit 2).
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

#if HAPSCENE_HAVE_HIL

TEST_CASE("hil pair cli: a 2-DOF run on two simulated boards exits 0, logs and shows both links") {
  const ScratchFolder folder("hil_pair_cli_run");
  const std::string scene =
      folder
          .write("pantograph_box.json",
                 R"({"name": "pantograph_box", "device": "hapkit_pantograph", "effects": [{"type": "box",
                    "min": ["55 mm", "115 mm"], "max": ["100 mm", "150 mm"], "stiffness": "300 N/m", "solid": "inside"}]})")
          .string();
  const std::string log = (folder.dir / "run.csv").string();
  const CliOutcome out = run_cli("run '" + scene + "' --device hil --sim-time --duration 1s --hand line --no-reload --quiet --log '" + log + "'");
  CHECK(out.exit_code == 0);
  for (const char* line : {"  joint 1 port     simulated board 1", "  joint 2 port     simulated board 2",
                           "  joint 1 board            hapkit firmware", "  joint 2 board            hapkit firmware",
                           "  two boards       "}) {
    CHECK_MESSAGE(out.out.find(line) != std::string::npos, line);
  }
  const std::string csv = slurp_file(log);
  CHECK(csv.starts_with("t_s,x_m,y_m,"));
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1001);
}

TEST_CASE("hil pair cli: a Haplink (encoder joints) is refused with exit 2, naming the joint") {
  const CliOutcome out = run_cli("run environments/planar/haplink_box_inside.json --device hil --sim-time");
  CHECK(out.exit_code == 2);
  CHECK(out.err.find("--device hil: profile \"haplink\" joint 1 reads an encoder") != std::string::npos);
}

#else

TEST_CASE("hil pair cli: needs simavr and the AVR toolchain" * doctest::skip()) {}

#endif
