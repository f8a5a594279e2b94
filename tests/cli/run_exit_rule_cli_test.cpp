// One rule for every N: a run that saw a non-finite force or a script disabled by a fault
// exits 1 and says so, in 1-D as in 2-D (docs/reference/exit-codes.md); so does a plot
// whose field or run met a script fault.
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
  write("faults2.lua", "n = 0\nfunction force(s) n = n + 1\n  if n > 10 then error(\"tenth call\") end\n"
                       "  return 0, 0 end\n");
  write("right.lua", "function force(s) if s.x > 0 then error(\"on the right\") end return 0, 0 end\n");
  write("fault_1d.json", R"({"effects": [{"type": "script", "file": "faults.lua"}]})");
  write("fault_2d.json", R"({"device": "haplink", "effects": [{"type": "script", "file": "faults2.lua"}]})");
  write("field_fault_2d.json", R"({"device": "haplink", "effects": [{"type": "script", "file": "right.lua"}]})");
  return dir;
}

}  // namespace

TEST_CASE("cli: a run that saw a non-finite force exits 1, whatever its axes") {
  const auto dir = write_fault_scenes();
  for (const std::string file : {"overflow_1d.json", "overflow_2d.json"}) {
    CAPTURE(file);
    const CliOutcome run = run_cli_in(dir.string(), "run " + file + " --sim-time --duration 50ms --no-reload");
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

TEST_CASE("cli: plot reports a script fault of its run or its field once and exits 1, whatever its axes") {
  const auto dir = write_fault_scenes();
  // The run's fault: the script fails on its eleventh call, 10 ms into the sweep.
  for (const std::string file : {"fault_1d.json", "fault_2d.json"}) {
    CAPTURE(file);
    const CliOutcome plot = run_cli_in(dir.string(), "plot " + file + " --output figure.svg");
    CHECK(plot.exit_code == 1);
    CHECK(occurrences(plot.err, "tenth call (first at t 0.010 s") == 1);
    CHECK(plot.err.find("of the sweep run)") != std::string::npos);
    CHECK(std::filesystem::exists(dir / "figure.svg"));  // the figure is still written
  }
  // The field's fault (fresh instances at each point): named once, with its first point.
  const CliOutcome field = run_cli_in(dir.string(), "plot field_fault_2d.json --output field.svg");
  CHECK(field.exit_code == 1);
  CHECK(occurrences(field.err, "right.lua:1: on the right (first at x ") == 1);
  std::filesystem::remove_all(dir);
}

}  // namespace hapscene::test
