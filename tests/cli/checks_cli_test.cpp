// The checking commands as users call them must not hide faults: probe and plot still
// write their output, print each script fault once (file:line: message) and exit 1;
// test fails the spec with the message; validate --quiet prints one line per file;
// an effect that never acts warns on every command.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using hapscene::test::run_cli;

namespace {

// Reads an undefined global only beyond 10 mm.
const char* kFaulting =
    "needs = {velocity = false, time = false}\n"
    "function force(s)\n"
    "  if s.x > 0.01 then return k * s.x end\n"
    "  return -100 * s.x\n"
    "end\n";

}  // namespace

TEST_CASE("cli: probe writes the CSV, prints a script fault once with file:line and exits 1") {
  const hapscene::test::ScratchFolder folder("checks_probe");
  const std::string script = folder.write("faulting.lua", kFaulting);
  const auto outcome = run_cli("probe " + script + " --x 0:20mm:5mm");
  CHECK(outcome.exit_code == 1);
  // Where the script faulted the force fields are empty: no silent 0 N.
  CHECK(outcome.out == "x_m,v_m_per_s,force_N,output_N\n0,0,0,0\n0.005,0,-0.5,-0.5\n0.01,0,-1,-1\n"
                       "0.015,0,,\n0.02,0,,\n");
  CHECK(outcome.err == script + ":3: undefined global 'k' (first at x 15.00 mm, v 0 m/s, t 0 s)\n");
  CHECK(hapscene::test::occurrences(outcome.err, "undefined global") == 1);
  // Backwards: the same rows, reversed, and the same message.
  const auto backwards = run_cli("probe " + script + " --x 20mm:0:-5mm");
  CHECK(backwards.exit_code == 1);
  CHECK(backwards.out == "x_m,v_m_per_s,force_N,output_N\n0.02,0,,\n0.015,0,,\n0.01,0,-1,-1\n"
                         "0.005,0,-0.5,-0.5\n0,0,0,0\n");
  CHECK(backwards.err == outcome.err);
}

TEST_CASE("cli: probe of a script with state does not depend on the order of the points") {
  const auto up = run_cli("probe scripts/mass_spring.lua --x -10mm:10mm:5mm");
  const auto down = run_cli("probe scripts/mass_spring.lua --x 10mm:-10mm:-5mm");
  const auto one = run_cli("probe scripts/mass_spring.lua --x 5mm:5mm:1mm");
  CHECK(up.exit_code == 0);
  CHECK(up.err.find("keeps state between calls") != std::string::npos);
  // Held still, the mass settles to the series spring (75 N/m): -0.375 N at 5 mm.
  CHECK(up.out.find("\n0.005,0,-0.37500000000000006,") != std::string::npos);
  CHECK(down.out.find("\n0.005,0,-0.37500000000000006,") != std::string::npos);
  CHECK(one.out.find("\n0.005,0,-0.37500000000000006,") != std::string::npos);
}

TEST_CASE("cli: probe --t evaluates a time-based script at that run time") {
  const auto at_zero = run_cli("probe scripts/vibration.lua --x 0:0:1mm");
  CHECK(at_zero.out == "x_m,v_m_per_s,force_N,output_N\n0,0,0,0\n");
  const auto later = run_cli("probe scripts/vibration.lua --x 0:0:1mm --t 3.125ms");
  CHECK(later.exit_code == 0);
  CHECK(later.out == "x_m,v_m_per_s,force_N,output_N\n0,0,0.5,0.5\n");
  CHECK(run_cli("probe scripts/vibration.lua --x 0:0:1mm --t -1s").exit_code == 2);
}

TEST_CASE("cli: plot still writes the figure, prints the fault once and exits 1") {
  const hapscene::test::ScratchFolder folder("checks_plot");
  const std::string script = folder.write("faulting.lua", kFaulting);
  const std::string svg = (folder.dir / "out.svg").string();
  const auto outcome = run_cli("plot " + script + " --output " + svg);
  CHECK(outcome.exit_code == 1);
  CHECK(std::filesystem::exists(svg));
  CHECK(hapscene::test::occurrences(outcome.err, "undefined global 'k'") == 1);
  CHECK(outcome.err.starts_with(script + ":3: undefined global 'k'"));
}

TEST_CASE("cli: test fails a spec whose script faults, printing the message") {
  const hapscene::test::ScratchFolder folder("checks_spec");
  folder.write("faulting.lua", kFaulting);
  const std::string spec = folder.write("faulting.test.json",
                                        R"({"environment": "faulting.lua", "forces": [{"x": "5 mm", "force": "-0.5 N"}]})");
  const auto outcome = run_cli("test " + spec);
  // (CI's AddressSanitizer stage once saw FAIL without this message: the output says why.)
  INFO("stdout: " << outcome.out << "\nstderr: " << outcome.err);
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.out.find("FAIL " + spec) != std::string::npos);
  CHECK(outcome.out.find("/environment: script fault: ") != std::string::npos);
  CHECK(outcome.out.find(":3: undefined global 'k'") != std::string::npos);
}

TEST_CASE("cli: errors of a spec's environment name the spec, /environment and the environment") {
  const hapscene::test::ScratchFolder folder("checks_missing");
  const std::string spec = folder.write("a.test.json", R"({"environment": "nothere.json"})");
  const auto outcome = run_cli("test " + spec);
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.err == "error: " + spec + ": /environment: " + (folder.dir / "nothere.json").string() +
                           ": cannot open file\n");
}

TEST_CASE("cli: validate --quiet prints one line per file with its verdict") {
  const auto outcome = run_cli("validate environments/wall.json tests/harness/specs/unstable_wall.json --quiet");
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.out ==
        "PASS wall (environments/wall.json): 60 checks, 3 not judged\n"
        "FAIL unstable_wall (tests/harness/specs/unstable_wall.json): 5 of 60 checks failed: sweep/slip, "
        "sweep/passivity, press/passivity, release/passivity, hold/passivity; 2 not judged\n");
}

TEST_CASE("cli: a wall that never acts warns on every command and fails validate") {
  const hapscene::test::ScratchFolder folder("checks_far");
  const std::string env = folder.write(
      "far.json", R"({"effects": [{"type": "wall", "position": 20, "stiffness": "500 N/m", "solid": "above"}]})");
  const std::string warning = "warning: " + env + ": /effects/0 (wall): position 20 m puts the solid side";
  const auto probe = run_cli("probe " + env + " --x 0:0:1mm");
  CHECK(probe.exit_code == 0);
  CHECK(probe.err.starts_with(warning));
  CHECK(probe.err.find("did you mean \"20 mm\"?") != std::string::npos);
  const auto validate = run_cli("validate " + env + " --quiet --scenario hold");
  CHECK(validate.exit_code == 1);
  CHECK(validate.err.starts_with(warning));
  CHECK(validate.out.find("failed: scene/effects") != std::string::npos);
  CHECK(run_cli("run " + env + " --sim-time --duration 10ms --quiet").err.starts_with(warning));
}

TEST_CASE("cli: a workspace too wide to sample is refused (exit 2), naming the environment and the profile") {
  const hapscene::test::ScratchFolder folder("checks_huge");
  std::string profile = hapscene::test::slurp_file(HAPSCENE_SOURCE_DIR "/environments/devices/hapkit3.json");
  const std::string from = R"("workspace": ["-50 mm", "45 mm"])";
  REQUIRE(profile.find(from) != std::string::npos);
  profile.replace(profile.find(from), from.size(), R"("workspace": ["-1000 m", "1000 m"])");
  const std::string profile_path = folder.write("big.json", profile);
  const std::string env = folder.write("env.json", R"({"device": "big.json", "effects": [{"type": "spring", "stiffness": 100}]})");
  const std::string message = "error: " + env + ": /device: " + profile_path +
                              ": the workspace [-1000, 1000] m spans 2000 m; the harness samples it every 20 um "
                              "and takes at most 1 m\n";
  for (const std::string command : {"validate ", "plot --output /dev/null "}) {
    const auto outcome = run_cli(command + env);
    CHECK(outcome.exit_code == 2);
    CHECK(outcome.err == message);
  }
  const std::string spec = folder.write("env.test.json", R"({"forces": [{"x": 0, "force": 0}]})");
  const auto tested = run_cli("test " + spec);
  CHECK(tested.exit_code == 2);
  CHECK(tested.err == "error: " + spec + ": /environment: " + message.substr(7));
}

TEST_CASE("cli: run reports a script fault with the time it happened and exits 1" * doctest::test_suite("threaded")) {
  // The hand sweeps from the left end of the workspace: the script faults when it first
  // passes 10 mm, well after the start, and does not declare time.
  const hapscene::test::ScratchFolder folder("checks_run");
  const std::string script = folder.write("faulting.lua", kFaulting);
  const auto outcome = run_cli("run " + script + " --sim-time --quiet --no-reload --duration 2s");
  CHECK(outcome.exit_code == 1);
  const std::size_t at = outcome.out.find("script disabled  " + script + ":3: undefined global 'k' (at t = ");
  REQUIRE(at != std::string::npos);
  const double fault_time_s = std::stod(outcome.out.substr(outcome.out.find("at t = ", at) + 7));
  CHECK(fault_time_s > 0.1);
  CHECK(fault_time_s < 2.0);
  // A clean script still exits 0.
  CHECK(run_cli("run scripts/spring.lua --sim-time --quiet --no-reload --duration 0.5s").exit_code == 0);
}

TEST_CASE("cli: a fault whose message changes at every point is printed a bounded number of times") {
  const hapscene::test::ScratchFolder folder("checks_flood");
  const std::string script = folder.write("distinct.lua",
      "function force(s)\n  if s.x > 0.001 then error(\"at \" .. math.floor(s.x * 1000 + 0.3) .. \" mm\") end\n"
      "  return 0\nend\n");
  // About 40 distinct messages (one per millimetre), each at 4 points.
  const auto up = run_cli("probe " + script + " --x -10mm:40mm:0.25mm");
  CHECK(up.exit_code == 1);
  CHECK(hapscene::test::occurrences(up.err, "\n") == 21);
  CHECK(up.err.find("... and script faults with other messages (only the 20 first") != std::string::npos);
  // The same faults are shown whichever way the points are probed.
  const auto down = run_cli("probe " + script + " --x 40mm:-10mm:-0.25mm");
  CHECK(down.err == up.err);
}
