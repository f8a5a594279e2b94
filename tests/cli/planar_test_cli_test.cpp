// `hapscene test` on 2-DOF specs end to end: a pass, a failure with the pointer and the
// numbers, an invalid spec (exit 2 with the place), the forms of the other dimension
// refused, the shipped specs found without arguments; and the open-loop CPU budget of
// 2-D `probe` and `test` for scripts with a slow top level or a slow force().
#include <doctest/doctest.h>

#include <chrono>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

namespace hapscene {
namespace {

const char* kBoxEnvironment = R"({"name": "box", "device": "haplink", "effects": [
  {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": "200 N/m", "solid": "inside"}]})";

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("planar test cli: a shipped 2-D spec passes, an unmet one fails with the pointer and the numbers") {
  const test::CliOutcome pass = test::run_cli("test environments/planar/haplink_box_inside.test.json");
  CAPTURE(pass.err);
  CHECK(pass.exit_code == 0);
  CHECK(pass.out.find("PASS environments/planar/haplink_box_inside.test.json (") == 0);
  CHECK(pass.out.find("1 specs, ") != std::string::npos);

  const test::ScratchFolder folder("planar_test_cli_fail");
  folder.write("box.json", kBoxEnvironment);
  const std::string spec = folder.write("box.test.json", R"({"forces": [
    {"at": ["-38 mm", "122 mm"], "force": ["-0.4 N", "0 N"], "tolerance": "1e-9 N"},
    {"at": ["-38 mm", "122 mm"], "force": ["1 N", "0 N"]}]})").string();
  const test::CliOutcome fail = test::run_cli("test '" + spec + "'");
  CHECK(fail.exit_code == 1);
  CHECK(fail.out.find("FAIL " + spec + " (2 expectations)\n") != std::string::npos);
  CHECK(fail.out.find("  FAIL /forces/1: force at (-38, 122) mm, v (0, 0) m/s: expected (1, 0) N +/- 1e-06 N, got "
                      "(-0.4, 0) N (off by 1.4 N)\n") != std::string::npos);
  CHECK(fail.out.find("/forces/0") == std::string::npos);  // met: printed only with --verbose
  const test::CliOutcome verbose = test::run_cli("test --verbose '" + spec + "'");
  CHECK(verbose.out.find("  ok   /forces/0: force at (-38, 122) mm") != std::string::npos);
}

TEST_CASE("planar test cli: an invalid 2-D spec or a form of the other dimension is exit 2 with its place") {
  const test::ScratchFolder folder("planar_test_cli_invalid");
  folder.write("box.json", kBoxEnvironment);
  const std::string spec = folder.write("box.test.json", R"({"forces": [{"x": "10 mm", "force": "1 N"}]})").string();
  const test::CliOutcome one_d_form = test::run_cli("test '" + spec + "'");
  CHECK(one_d_form.exit_code == 2);
  CHECK(one_d_form.err.find(spec + ": /forces/0/x: a 1-D spec's form: this spec's environment is 2-DOF") !=
        std::string::npos);
  CHECK(one_d_form.out.find("FAIL " + spec + ": invalid input") != std::string::npos);

  folder.write("wall.json", R"({"name": "w", "effects": [{"type": "wall", "position": "10 mm", "stiffness": "100 N/m"}]})");
  const std::string wall_spec =
      folder.write("wall.test.json", R"({"forces": [{"at": ["10 mm", "0 mm"], "force": [0, 0]}]})").string();
  const test::CliOutcome two_d_form = test::run_cli("test '" + wall_spec + "'");
  CHECK(two_d_form.exit_code == 2);
  CHECK(two_d_form.err.find(wall_spec + ": /forces/0/at: a 2-D spec's form: this spec's environment is 1-DOF, so a "
                                        "point is \"x\": X") != std::string::npos);

  // One invalid spec among good ones: the others still run, the exit code is 2.
  const test::CliOutcome mixed =
      test::run_cli("test environments/planar/haplink_circle_inside.test.json '" + spec + "'");
  CHECK(mixed.exit_code == 2);
  CHECK(mixed.out.find("PASS environments/planar/haplink_circle_inside.test.json") != std::string::npos);
}

// A planar scene's script whose top level takes ~0.3 s (its load budget raised) and that
// keeps state: every open-loop point needs a fresh instance.
TEST_CASE("planar test cli: probe and test of a 2-D script with a slow top level end early, exit 2") {
  const test::ScratchFolder folder("planar_slow_load_cli");
  folder.write("slow.lua",
               "needs = {velocity = false, time = false}\n"
               "local a = 0\n"
               "for i = 1, 30000000 do a = a + i end\n"
               "local calls = 0\n"
               "function force(s)\n"
               "  calls = calls + 1\n"
               "  return -0.001 * calls, 0\n"
               "end\n");
  const std::string env = folder.write("slow.json", R"({"name": "slow", "device": "haplink", "effects": [
    {"type": "script", "file": "slow.lua", "limits": {"instructions_at_load": 1000000000}}]})").string();
  const std::string spec = folder.write("slow.test.json", R"({"environment": "slow.json",
    "zero_outside": {"min": ["-1 mm", "100 mm"], "max": ["1 mm", "120 mm"]}})").string();
  for (const std::string& args : {"probe '" + env + "' --x -50mm:49mm:1mm --y 100mm:109mm:1mm", "test '" + spec + "'"}) {
    CAPTURE(args);
    const auto start = std::chrono::steady_clock::now();
    const test::CliOutcome outcome = test::run_cli(args);
    // Without the budget: 1000 (or 8436) points x 0.3 s. With it a few seconds of CPU.
    CHECK(seconds_since(start) < 60.0);
    CAPTURE(outcome.err);
    CHECK(outcome.exit_code == 2);
    CHECK(outcome.err.find("slow.lua: creating a fresh instance takes ") != std::string::npos);
    CHECK(outcome.err.find(" s of CPU time (its top-level code runs every time); this open-loop evaluation of ") !=
          std::string::npos);
    CHECK(outcome.err.find(" s budget: fewer points (probe --x), or a cheaper top level") != std::string::npos);
  }
}

TEST_CASE("planar test cli: a slow top level without state still probes, a slow force() fails a spec at once") {
  const test::ScratchFolder folder("planar_slow_cli");
  folder.write("slow_load.lua",
               "needs = {velocity = false, time = false}\n"
               "local a = 0\n"
               "for i = 1, 10000000 do a = a + i end\n"
               "function force(s) return -10 * s.x, -10 * s.y end\n");
  const std::string env = folder.write("slow_load.json", R"({"name": "slow", "device": "haplink", "effects": [
    {"type": "script", "file": "slow_load.lua", "limits": {"instructions_at_load": 1000000000}}]})").string();
  const test::CliOutcome probe = test::run_cli("probe '" + env + "' --x 0:0.009:0.001 --y 0.1:0.109:0.001");
  CAPTURE(probe.err);
  CHECK(probe.exit_code == 0);
  CHECK(probe.out.find("\n0.001,0.1,0,0,-0.01,-1,-0.01,-1\n") != std::string::npos);

  folder.write("slow_call.lua",
               "needs = {velocity = false, time = false}\n"
               "function force(s)\n"
               "  local a = 0\n"
               "  for i = 1, 3000000 do a = a + i end\n"
               "  return 0, 0\n"
               "end\n");
  folder.write("slow_call.json", R"({"name": "slow", "device": "haplink", "effects": [
    {"type": "script", "file": "slow_call.lua", "limits": {"instructions_per_call": 100000000}}]})");
  const std::string spec = folder.write("slow_call.test.json", R"({"never_exceeds": "1 N"})").string();
  const auto start = std::chrono::steady_clock::now();
  const test::CliOutcome outcome = test::run_cli("test '" + spec + "'");
  CHECK(seconds_since(start) < 60.0);
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.out.find("  FAIL /environment: too slow for the 1000 Hz loop: force() took ") != std::string::npos);
}

TEST_CASE("planar test cli: a folder stands for every spec under it") {
  const test::CliOutcome folder = test::run_cli("test scripts/planar");
  CHECK(folder.exit_code == 0);
  CHECK(folder.out.find("7 specs, ") != std::string::npos);
  CHECK(folder.out.find("PASS scripts/planar/maze.test.json") != std::string::npos);
  const test::ScratchFolder empty("planar_test_cli_empty_folder");
  const test::CliOutcome none = test::run_cli("test '" + empty.dir.string() + "'");
  CHECK(none.exit_code == 2);
  CHECK(none.err.find("no *.test.json under ") != std::string::npos);
}

}  // namespace hapscene
