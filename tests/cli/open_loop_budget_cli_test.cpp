// The open-loop evaluations (probe, validate's field scan, test specs, plot) create fresh
// script instances, each re-running the script's top level. A script whose top level
// takes ~0.3 s (well within its load budget) and keeps state would make them take
// minutes to hours; they must end within a bound, refusing with a message that names the
// script, its creation time and the number of points (exit 2). And `plot` of a script
// too slow for the loop exits 1 with the pace message once.
#include <doctest/doctest.h>

#include <chrono>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

namespace hapscene {
namespace {

// ~30 M loop iterations at the top level (about 0.3 s here), and state between calls.
const char* kSlowLoadStatefulScript =
    "needs = {velocity = false, time = false}\n"
    "local a = 0\n"
    "for i = 1, 30000000 do a = a + i end\n"
    "local calls = 0\n"
    "function force(s)\n"
    "  calls = calls + 1\n"
    "  return -0.001 * calls\n"
    "end\n";
// A top level of ~0.1 s without state: the scan needs a fixed number of instances.
const char* kSlowLoadStatelessScript =
    "needs = {velocity = false, time = false}\n"
    "local a = 0\n"
    "for i = 1, 10000000 do a = a + i end\n"
    "function force(s) return -10 * s.x end\n";
const char* kEnvironment =
    R"({"name": "slow", "effects": [{"type": "script", "file": "slow.lua", "limits": {"instructions_at_load": 1000000000}}]})";

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Runs `hapscene ARGS` and checks it ends within `bound_s` with the budget message.
test::CliOutcome check_refused(const std::string& args, double bound_s) {
  CAPTURE(args);
  const auto start = std::chrono::steady_clock::now();
  const test::CliOutcome outcome = test::run_cli(args);
  CHECK(seconds_since(start) < bound_s);
  CAPTURE(outcome.err);
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.err.find("slow.lua: creating a fresh instance takes ") != std::string::npos);
  CHECK(outcome.err.find(" s of CPU time (its top-level code runs every time); this open-loop evaluation of ") !=
        std::string::npos);
  CHECK(outcome.err.find(" s budget: fewer points (probe --x), or a cheaper top level") != std::string::npos);
  return outcome;
}

}  // namespace

TEST_CASE("open-loop budget: probe, validate, test and plot of a script with a slow top level end early") {
  const test::ScratchFolder folder("slow_load_cli");
  folder.write("slow.lua", kSlowLoadStatefulScript);
  const std::string env = (folder.dir / "slow.json").string();
  folder.write("slow.json", kEnvironment);
  const std::string spec =
      folder.write("slow.test.json", R"({"environment": "slow.json", "zero_outside": ["-1 mm", "1 mm"]})").string();
  // Without the budget: 1000 points x 0.3 s = 5 minutes; validate and test each more than
  // 90 s. With it, each takes a few seconds of CPU (the bound leaves room for sanitizers
  // and a busy machine).
  const test::CliOutcome probe = check_refused("probe '" + env + "' --x 0:0.999:0.001", 60.0);
  CHECK(probe.err.find("this open-loop evaluation of 1000 points needs 1000 more") != std::string::npos);
  check_refused("validate '" + env + "'", 60.0);
  check_refused("test '" + spec + "'", 60.0);
  check_refused("plot '" + env + "' --output '" + (folder.dir / "slow.svg").string() + "'", 60.0);
}

TEST_CASE("open-loop budget: a slow top level without state still probes (a fixed number of instances)") {
  const test::ScratchFolder folder("slow_load_stateless_cli");
  folder.write("slow.lua", kSlowLoadStatelessScript);
  folder.write("slow.json", kEnvironment);
  const test::CliOutcome outcome = test::run_cli("probe '" + (folder.dir / "slow.json").string() + "' --x 0:0.009:0.001");
  CAPTURE(outcome.err);
  CHECK(outcome.exit_code == 0);
  CHECK(outcome.out.find("0.001,0,-0.01,-0.01\n") != std::string::npos);
}

TEST_CASE("plot: a script too slow for the loop writes the figure, prints the pace message once and exits 1") {
  const test::ScratchFolder folder("slow_plot_cli");
  folder.write("slow.lua",
               "needs = {velocity = false, time = false}\n"
               "function force(s)\n"
               "  local a = 0\n"
               "  for i = 1, 3000000 do a = a + i end\n"
               "  return 0\n"
               "end\n");
  const std::string env =
      folder.write("slow.json",
                   R"({"name": "slow", "effects": [{"type": "script", "file": "slow.lua", "limits": {"instructions_per_call": 100000000}}]})")
          .string();
  const std::string svg = (folder.dir / "slow.svg").string();
  const test::CliOutcome outcome = test::run_cli("plot '" + env + "' --output '" + svg + "'");
  CAPTURE(outcome.err);
  CHECK(outcome.exit_code == 1);
  CHECK(std::filesystem::exists(svg));
  const std::string message = "pace: too slow for the 1000 Hz loop: ";
  const std::size_t first = outcome.err.find(message);
  CHECK(first != std::string::npos);
  CHECK(outcome.err.find(message, first + 1) == std::string::npos);
}

}  // namespace hapscene
