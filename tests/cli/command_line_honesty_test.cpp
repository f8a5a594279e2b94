// The command line never lies: bench reports a script that a fault disabled (its rows
// timed 0 N) and labels rows by what they run; validate and test give every file its
// verdict when one of them is invalid input; a failed write of standard output says why.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using hapscene::test::run_cli;

namespace {

// Reads an undefined global only beyond 2 mm (the bench's sweeping hand gets there).
const char* kFaultingScript =
    "needs = {velocity = false, time = false}\n"
    "function force(s)\n"
    "  if s.x > 0.002 then return k * s.x end\n"
    "  return -100 * s.x\n"
    "end\n";

const char* kSpringScript =
    "needs = {velocity = false, time = false}\n"
    "function force(s) return -100 * s.x end\n";

// Runs `hapscene ARGS` with standard output on /dev/full: the exit code and stderr.
hapscene::test::CliOutcome run_cli_to_full_disk(const std::string& args) {
  const hapscene::test::ScratchFolder folder("honest_full_disk");
  const std::string err_path = (folder.dir / "err").string();
  const std::string command = "cd '" HAPSCENE_SOURCE_DIR "' && '" HAPSCENE_BINARY "' " + args +
                              " >/dev/full 2>'" + err_path + "' </dev/null";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, "", hapscene::test::slurp_file(err_path)};
}

}  // namespace

TEST_CASE("cli: bench reports a script fault once with file:line and exits 1") {
  const hapscene::test::ScratchFolder folder("honest_bench");
  const std::string script = folder.write("faulting.lua", kFaultingScript);
  const auto outcome = run_cli("bench " + script + " --seconds 0.2 --passes 1");
  CHECK(outcome.exit_code == 1);
  CHECK(hapscene::test::occurrences(outcome.err, script + ":3: undefined global 'k' (while timing faulting, Lua script)\n") == 1);
  CHECK(outcome.err.find("its rows timed 0 N") != std::string::npos);
  // The table is still printed, and the row says it runs a Lua script.
  CHECK(outcome.out.find("faulting   Lua script ") != std::string::npos);

  const auto callgrind = run_cli("bench --callgrind " + script + " --ticks 2000");
  CHECK(callgrind.exit_code == 1);
  CHECK(hapscene::test::occurrences(callgrind.err, script + ":3: undefined global 'k'") == 1);
}

TEST_CASE("cli: bench labels a .lua environment and a mixed one by what they run, and exits 0 without faults") {
  const hapscene::test::ScratchFolder folder("honest_bench_labels");
  const std::string script = folder.write("lspring.lua", kSpringScript);
  const std::string mixed = folder.write(
      "mixed.json", R"({"name": "mixed", "effects": [{"type": "spring", "stiffness": 10},
      {"type": "script", "file": "lspring.lua"}]})");
  const auto outcome = run_cli("bench " + script + " " + mixed + " --seconds 0.2 --passes 1");
  CHECK(outcome.exit_code == 0);
  CHECK(outcome.err.empty());
  CHECK(outcome.out.find("lspring    Lua script ") != std::string::npos);
  CHECK(outcome.out.find("mixed      built-in + Lua ") != std::string::npos);
  CHECK(outcome.out.find("built-in (JSON)") == std::string::npos);
}

TEST_CASE("cli: bench treats a 2-D environment's rows as a 1-D one's: labelled by what they run, a fault reported") {
  const hapscene::test::ScratchFolder folder("honest_bench_planar");
  // Reads an undefined global only in the upper part of the Haplink's workspace.
  folder.write("faulting_2d.lua",
               "needs = {velocity = false, time = false}\n"
               "function force(s)\n"
               "  if s.y > 0.14 then return k * s.x, 0 end\n"
               "  return -100 * s.x, 0\n"
               "end\n");
  const std::string faulting = folder.write(
      "faulting_2d.json", R"({"name": "faulting_2d", "device": "haplink", "effects": [{"type": "script", "file": "faulting_2d.lua"}]})");
  const auto outcome = run_cli("bench " + faulting + " --seconds 0.2 --passes 1");
  CHECK(outcome.exit_code == 1);
  CHECK(hapscene::test::occurrences(outcome.err, "faulting_2d.lua:3: undefined global 'k' (while timing faulting_2d, Lua script)\n") == 1);
  CHECK(outcome.out.find("faulting_2d              Lua script ") != std::string::npos);
  CHECK(outcome.out.find("built-in (JSON)") == std::string::npos);
  CHECK(outcome.out.find("Lua rows: p99.9 <= 5x the median (no GC spikes): ") != std::string::npos);

  // A built-in 2-D spring is timed beside its Lua twin, as a 1-D lab effect is.
  const std::string spring = folder.write(
      "spring_2d.json", R"({"name": "spring_2d", "device": "haplink", "effects": [{"type": "spring", "stiffness": 100, "center": [0, 0.12]}]})");
  const auto twin = run_cli("bench " + spring + " --seconds 0.2 --passes 1");
  CHECK(twin.exit_code == 0);
  const std::size_t builtin = twin.out.find("spring_2d                built-in (JSON) ");
  const std::size_t lua = twin.out.find("spring_2d                Lua script ");
  REQUIRE(builtin != std::string::npos);
  REQUIRE(lua != std::string::npos);
  CHECK(builtin < lua);
}

TEST_CASE("cli: validate gives every file its verdict when one is invalid input") {
  const hapscene::test::ScratchFolder folder("honest_validate_many");
  const std::string bad = folder.write("bad.json", "{\"effects\": [");
  const auto quiet = run_cli("validate --quiet --scenario hold environments/spring.json " + bad +
                             " environments/damper.json");
  CHECK(quiet.exit_code == 2);
  CHECK(quiet.out.starts_with("PASS spring (environments/spring.json): "));
  CHECK(quiet.out.find("FAIL " + bad + ": invalid input (see the error above)\n") != std::string::npos);
  CHECK(quiet.out.find("PASS damper (environments/damper.json): ") != std::string::npos);
  CHECK(hapscene::test::occurrences(quiet.err, "error: " + bad + ":1:") == 1);

  // Without --quiet: both tables, the error once.
  const auto tables = run_cli("validate --scenario hold " + bad + " environments/spring.json");
  CHECK(tables.exit_code == 2);
  CHECK(tables.out.find("validate spring (environments/spring.json)") != std::string::npos);

  // A failed check and an invalid file: invalid input wins (2); a failed check alone is 1.
  const auto failing = run_cli("validate --quiet environments/wall.json tests/harness/specs/unstable_wall.json " + bad);
  CHECK(failing.exit_code == 2);
  CHECK(run_cli("validate --quiet tests/harness/specs/unstable_wall.json").exit_code == 1);
}

TEST_CASE("cli: test runs every spec when one cannot be loaded") {
  const hapscene::test::ScratchFolder folder("honest_test_many");
  const std::string bad = folder.write("bad.test.json", "{\"environment\": ");
  const auto outcome = run_cli("test environments/spring.test.json " + bad + " environments/damper.test.json");
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.out.find("PASS environments/spring.test.json") != std::string::npos);
  CHECK(outcome.out.find("FAIL " + bad + ": invalid input (see the error above)\n") != std::string::npos);
  CHECK(outcome.out.find("PASS environments/damper.test.json") != std::string::npos);
  CHECK(outcome.out.find("3 specs, ") != std::string::npos);
  CHECK(outcome.out.find("1 specs failed") != std::string::npos);
  CHECK(hapscene::test::occurrences(outcome.err, "error: " + bad) == 1);
}

TEST_CASE("cli: a failed write of standard output names the cause and exits 1") {
  for (const std::string command :
       {"probe environments/spring.json --x 0:10mm:1mm", "validate --quiet --scenario hold environments/spring.json",
        "test environments/spring.test.json", "--version", "help"}) {
    CAPTURE(command);
    const auto outcome = run_cli_to_full_disk(command);
    CHECK(outcome.exit_code == 1);
    CHECK(outcome.err.find("hapscene: standard output: write failed: No space left on device\n") != std::string::npos);
    CHECK(outcome.err.find("unknown error") == std::string::npos);
  }
}
