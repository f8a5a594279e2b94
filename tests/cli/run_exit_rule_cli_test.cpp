// One rule for every N: a run that saw a non-finite force or a script disabled by a fault
// exits 1 and says so, in 1-D as in 2-D (docs/reference/exit-codes.md).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/cli/cli_support.hpp"

namespace hapscene::test {
namespace {

// A folder of environments whose forces the safety stage must zero: two scripts whose
// finite forces sum past the largest double, and one script that faults on its tenth call.
std::filesystem::path write_fault_scenes() {
  const auto dir = std::filesystem::temp_directory_path() / ("hapscene_exit_rule_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const char* name, const std::string& text) { std::ofstream(dir / name) << text; };
  write("huge.lua", "function force(s) return 1e308 end\n");
  write("huge2.lua", "function force(s) return 1e308, 1e308 end\n");
  write("faults.lua", "n = 0\nfunction force(s) n = n + 1\n  if n > 10 then error(\"tenth call\") end\n"
                      "  return 0 end\n");
  write("overflow_1d.json", R"({"effects": [{"type": "script", "file": "huge.lua"},
                                            {"type": "script", "file": "huge.lua"}]})");
  write("overflow_2d.json", R"({"device": "haplink", "effects": [{"type": "script", "file": "huge2.lua"},
                                                                 {"type": "script", "file": "huge2.lua"}]})");
  write("fault_1d.json", R"({"effects": [{"type": "script", "file": "faults.lua"}]})");
  return dir;
}

}  // namespace

TEST_CASE("cli: a run that saw a non-finite force exits 1, whatever its axes") {
  const auto dir = write_fault_scenes();
  for (const char* file : {"overflow_1d.json", "overflow_2d.json"}) {
    CAPTURE(file);
    const CliOutcome run = run_cli_in(dir.string(), std::string("run ") + file + " --sim-time --duration 50ms --no-reload");
    CHECK(run.exit_code == 1);
    // The summary counts each zeroed tick; the commanded force stayed zero.
    CHECK(run.out.find("  faults           50 non-finite forces\n") != std::string::npos);
    CHECK(run.out.find("commanded 0.000 N") != std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("cli: a run whose script was disabled by a fault exits 1") {
  const auto dir = write_fault_scenes();
  const CliOutcome run = run_cli_in(dir.string(), "run fault_1d.json --sim-time --duration 50ms --no-reload");
  CHECK(run.exit_code == 1);
  CHECK(occurrences(run.err + run.out, "tenth call") >= 1);
  std::filesystem::remove_all(dir);
}

}  // namespace hapscene::test
