// The `hapscene` command as users call it: output formats and exit codes
// (0 success, 2 invalid input, 1 anything else).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/cli/cli_support.hpp"

namespace {

using Outcome = hapscene::test::CliOutcome;
using hapscene::test::run_cli;

}  // namespace

TEST_CASE("cli: probe prints the force-displacement curve as CSV") {
  const Outcome probe = run_cli("probe environments/wall.json --x -5mm:20mm:5mm");
  CHECK(probe.exit_code == 0);
  CHECK(probe.out ==
        "x_m,v_m_per_s,force_N,output_N\n"
        "-0.005,0,0,0\n"
        "0,0,0,0\n"
        "0.005,0,0,0\n"
        "0.01,0,0,0\n"
        "0.015,0,-2.4999999999999996,-2.4999999999999996\n"
        "0.02,0,-5,-5\n");
  CHECK(probe.err.empty());
}

TEST_CASE("cli: probe shows the safety clamp and the workspace limit in output_N") {
  const Outcome probe = run_cli("probe environments/wall.json --x 0.02:0.05:0.01");
  CHECK(probe.out ==
        "x_m,v_m_per_s,force_N,output_N\n"
        "0.02,0,-5,-5\n"
        "0.03,0,-9.999999999999998,-6\n"  // -500 * (0.03 - 0.01) in doubles; clamped to the Hapkit profile's 6 N
        "0.04,0,-15,-6\n"
        "0.05,0,-20,0\n");     // outside the workspace (+45 mm): nothing rendered
}

TEST_CASE("cli: probe with a velocity shows velocity-dependent effects") {
  const Outcome probe = run_cli("probe environments/texture.json --x 0:10mm:2.5mm --v 0.1");
  CHECK(probe.out ==
        "x_m,v_m_per_s,force_N,output_N\n"
        "0,0.1,-0.2,-0.2\n"
        "0.0025,0.1,-0.2,-0.2\n"
        "0.005,0.1,0,0\n"
        "0.0075,0.1,0,0\n"
        "0.01,0.1,-0.2,-0.2\n");
  CHECK(run_cli("probe environments/texture.json --x 0.01:0:-0.01 --v -50mm/s").out ==
        "x_m,v_m_per_s,force_N,output_N\n0.01,-0.05,0.1,0.1\n0,-0.05,0.1,0.1\n");
}

TEST_CASE("cli: invalid input exits with 2 and says where") {
  const Outcome missing_x = run_cli("probe environments/wall.json");
  CHECK(missing_x.exit_code == 2);
  CHECK(missing_x.err == "error: hapscene probe: --x START:STOP:STEP is required\n");

  CHECK(run_cli("probe environments/wall.json --x 0:1").err ==
        "error: hapscene probe: --x: expected START:STOP:STEP, got \"0:1\"\n");
  CHECK(run_cli("probe environments/wall.json --x 0:1:0").err ==
        "error: hapscene probe: --x: STEP must not be 0\n");
  CHECK(run_cli("probe environments/wall.json --x 0:1:-0.1").err ==
        "error: hapscene probe: --x: STEP goes away from STOP\n");
  CHECK(run_cli("probe environments/wall.json --x 0:10:1e-6").err ==
        "error: hapscene probe: --x: more than 1000000 points\n");
  CHECK(run_cli("probe environments/wall.json --x 0:1N:0.1").err ==
        "error: hapscene probe: --x STOP: expected a length (m), got a force (\"1N\")\n");
  CHECK(run_cli("probe environments/wall.json --x 0:1:0.1 --speed 3").err ==
        "error: hapscene probe: unknown option --speed\n");

  const Outcome no_file = run_cli("probe environments/nope.json --x 0:1:0.5");
  CHECK(no_file.exit_code == 2);
  CHECK(no_file.err == "error: environments/nope.json: cannot open file\n");

  const Outcome bad_device = run_cli("run environments/wall.json --device usb");
  CHECK(bad_device.exit_code == 2);
  CHECK(bad_device.err == "error: hapscene run: --device: unknown device \"usb\" (available: sim, serial:PATH, hil)\n");

  // Device specs and link options.
  const Outcome no_port = run_cli("run environments/wall.json --device serial:/dev/hapscene-none");
  CHECK(no_port.exit_code == 2);
  CHECK(no_port.err == "error: hapscene run: --device serial:/dev/hapscene-none: cannot open "
                       "/dev/hapscene-none: No such file or directory (no such port: is the board plugged in? "
                       "`hapscene devices` lists the ports that look like boards)\n");
  CHECK(run_cli("run environments/wall.json --device serial:").err ==
        "error: hapscene run: --device serial: needs a port path, e.g. serial:/dev/ttyACM0\n");
  const Outcome bad_baud = run_cli("run environments/wall.json --device serial:/dev/null --baud 12345");
  CHECK(bad_baud.exit_code == 2);
  CHECK(bad_baud.err.starts_with("error: hapscene run: --baud: 12345 is not a rate the serial port offers (9600, "));
  CHECK(run_cli("run environments/wall.json --baud fast").err ==
        "error: hapscene run: --baud: expected a positive whole number of bits per second in [1, 100000000], got "
        "\"fast\"\n");
  CHECK(run_cli("run environments/wall.json --device hil:/nonexistent.elf").exit_code == 2);

  CHECK(run_cli("").exit_code == 2);
  CHECK(run_cli("frobnicate").exit_code == 2);
  CHECK(run_cli("--help").exit_code == 0);
}

TEST_CASE("cli: run checks every file before running any") {
  const auto bad = std::filesystem::temp_directory_path() / "hapscene_bad_env.json";
  {
    std::ofstream out(bad);
    out << "{\"effects\": [{\"type\": \"wal\", \"position\": 0}]}";
  }
  const Outcome run = run_cli("run --sim-time environments/wall.json " + bad.string());
  std::filesystem::remove(bad);
  CHECK(run.exit_code == 2);
  CHECK(run.out.empty());
  CHECK(run.err == "error: " + bad.string() +
                       ": /effects/0/type: unknown effect type \"wal\" (did you mean \"wall\"?)\n");
}

TEST_CASE("cli: run prints a summary per environment" * doctest::test_suite("threaded")) {
  const Outcome run =
      run_cli("run --sim-time --duration 0.5s environments/spring.json environments/wall.json");
  CHECK(run.exit_code == 0);
  CHECK(run.out.find("spring (environments/spring.json) on sim:hapkit3, 1000 Hz, simulated time, hand sweep\n"
                     "  ticks            500 in 0.500 s of device time, loop rate 1000.0 Hz\n") == 0);
  CHECK(run.out.find("\nwall (environments/wall.json) on sim:hapkit3") != std::string::npos);
  for (const char* line : {"  max force        asked ", "  time clamped     ", "  faults           0 non-finite",
                           "  deadline misses  n/a", "  tick compute     p50 "}) {
    CAPTURE(line);
    CHECK(run.out.find(line) != std::string::npos);
  }
  CHECK(run.err.empty());  // no status line when stderr is not a terminal
}
