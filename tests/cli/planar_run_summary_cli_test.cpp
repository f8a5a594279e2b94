// `hapscene run` on a 2-DOF environment prints the summary 1-D runs print, from the same
// printer (engine/cli/run_summary.cpp): deadline misses and tick timing (real-time jitter
// lines in real time), every safety counter including the linkage's, and a disabled
// script once, with when and where (t and the handle's x, y).
#include <doctest/doctest.h>

#include <cmath>
#include <regex>
#include <sstream>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

TEST_CASE("planar run summary: simulated time has the 1-D lines, the linkage's counters and no jitter lines") {
  const CliOutcome run =
      run_cli("run environments/planar/haplink_box_inside.json --sim-time --duration 0.3s --hand circle --quiet");
  REQUIRE(run.exit_code == 0);
  CHECK(run.out.starts_with("haplink_box_inside (environments/planar/haplink_box_inside.json) on sim:haplink, "
                            "1000 Hz, simulated time, hand circle\n"
                            "  ticks            300 in 0.300 s of device time, loop rate 1000.0 Hz\n"));
  for (const char* line : {"  max force        asked ", "  time clamped     ", "  linkage          ",
                           "  faults           0 non-finite forces\n", "  deadline misses  n/a (simulated time)\n",
                           "  tick compute     p50 ", "  plant            0 linkage faults"}) {
    CAPTURE(line);
    CHECK(occurrences(run.out, line) == 1);
  }
  CHECK(std::regex_search(run.out, std::regex("  linkage          [0-9]+ ticks near a singular pose or unreachable "
                                               "\\(force held\\), [0-9]+ with a saturated motor \\(both scaled\\)\n")));
  CHECK(run.out.find("wake-up jitter") == std::string::npos);
  // The order of the 1-D summary: counters, scripts, then timing.
  CHECK(run.out.find("  faults") < run.out.find("  deadline misses"));
  CHECK(run.out.find("  deadline misses") < run.out.find("  tick compute"));
}

TEST_CASE("planar run summary: real time counts deadline misses and prints the jitter lines" *
          doctest::test_suite("threaded")) {
  const CliOutcome run = run_cli("run environments/planar/haplink_box_inside.json --duration 0.2s --quiet");
  REQUIRE(run.exit_code == 0);
  CHECK(run.out.find(", real time, hand sweep\n") != std::string::npos);
  CHECK(std::regex_search(run.out, std::regex("\n  deadline misses  [0-9]+\n")));
  CHECK(std::regex_search(run.out, std::regex("\n  wake-up jitter   p50 [0-9.]+ us  p99 [0-9.]+ us  max [0-9.]+ us\n")));
  CHECK(std::regex_search(run.out, std::regex("\n  jitter bands     <10us [0-9]+  10-50us [0-9]+  50-100us [0-9]+  "
                                               "100-500us [0-9]+  0.5-1ms [0-9]+  >1ms [0-9]+\n")));
  CHECK(run.out.find("\n  scheduling       ") != std::string::npos);
}

TEST_CASE("planar run summary: a script fault is reported once with its time and the handle's place") {
  ScratchFolder scratch("planar_summary_fault");
  const auto env = scratch.write(
      "env.json",
      R"({"name": "t", "device": "haplink", "effects": [{"type": "script", "source": )"
      R"("function force(s) if s.t > 0.2 then error('broke') end return 0, 0 end"}]})");
  const std::string log = (scratch.dir / "run.csv").string();
  const CliOutcome run =
      run_cli("run '" + env.string() + "' --sim-time --duration 0.5s --hand circle --quiet --log '" + log + "'");
  CHECK(run.exit_code == 1);
  std::smatch match;
  REQUIRE(std::regex_search(run.out, match,
                            std::regex("  script disabled  .*:1: broke \\(at t = ([0-9.]+) s, x (-?[0-9.]+) mm, "
                                       "y (-?[0-9.]+) mm; 0 N for the remaining ([0-9]+) ticks\\)\n")));
  CHECK(occurrences(run.out, "script disabled") == 1);
  const double t_s = std::stod(match[1]);
  CHECK(t_s > 0.1995);
  CHECK(t_s < 0.2015);
  CHECK(std::labs(std::stol(match[4]) + std::lround(t_s * 1000.0) - 499) <= 1);  // the ticks after the fault
  // The place is the handle the host measured at that tick (the --log row of t).
  std::istringstream rows(slurp_file(log));
  std::string row;
  std::getline(rows, row);  // header
  bool found = false;
  while (std::getline(rows, row)) {
    std::istringstream cells(row);
    std::string t, x, y;
    std::getline(cells, t, ',');
    std::getline(cells, x, ',');
    std::getline(cells, y, ',');
    if (std::fabs(std::stod(t) - t_s) > 1e-9) continue;
    found = true;
    // Printed to 0.01 mm.
    CHECK(std::fabs(std::stod(match[2]) - std::stod(x) * 1e3) <= 0.0051);
    CHECK(std::fabs(std::stod(match[3]) - std::stod(y) * 1e3) <= 0.0051);
  }
  CHECK(found);
}
