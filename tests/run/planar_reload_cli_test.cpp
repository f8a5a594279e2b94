// Hot reload in a 2-DOF `hapscene run`, driven as the 1-D tests drive it (a thread edits
// the files while the run goes): an edit cross-fades in and the summary reports it and
// the limit it tightened; an invalid edit keeps the running scene and prints its located
// error once; a 1-DOF file or another device profile in its place is refused.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;

namespace {

// A planar environment on `device` with a 2-D spring 20 mm to the right of the haplink's
// home (about 4 N at 200 N/m: the profile's 2 N limit holds it) and `extra` keys.
std::string spring_env(const std::string& device, const std::string& extra = "", const std::string& stiffness = "\"200 N/m\"") {
  return R"({"name": "s", "device": ")" + device + "\", " + extra +
         R"("effects": [{"type": "spring", "stiffness": )" + stiffness +
         R"(, "center": ["3.67 mm", "142.34 mm"]}]})";
}


// The largest commanded force magnitude in the --log rows from `from_s` on.
double largest_output_N(const std::string& csv, double from_s) {
  std::istringstream rows(csv);
  std::string row;
  std::getline(rows, row);
  double largest = 0.0;
  while (std::getline(rows, row)) {
    std::istringstream cells(row);
    std::string cell[9];
    for (std::string& c : cell) std::getline(cells, c, ',');
    if (std::stod(cell[0]) < from_s) continue;
    largest = std::max(largest, std::hypot(std::stod(cell[7]), std::stod(cell[8])));
  }
  return largest;
}

}  // namespace

TEST_CASE("planar run reload: an edit cross-fades in, the summary counts it and names the tightened limit" *
          doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("planar_reload_take");
  const auto env = scratch.write("env.json", spring_env("haplink"));
  const std::string log = (scratch.dir / "run.csv").string();
  std::thread editor([&] {
    // After the 0.5 s soft start.
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
    // The new version adds a shape (a cage round the workspace): its proxy's run state is
    // made off the loop (before, a planar reload adding a shape crashed the run).
    std::string next = spring_env("haplink", R"("safety": {"max_force": "1 N"}, )");
    next.replace(next.rfind("]}"), 2, R"(, {"type": "box", "min": ["-60 mm", "95 mm"], "max": ["35 mm", "160 mm"], )"
                                      R"("stiffness": "100 N/m", "solid": "outside"}]})");
    scratch.write("env.json", next);
  });
  const test::CliOutcome run = test::run_cli("run " + env.string() +
                                             " --duration 2.4s --hand hold --hand-stiffness 2000 --quiet --log '" +
                                             log + "'");
  editor.join();
  CHECK(run.exit_code == 0);
  CHECK_MESSAGE(test::occurrences(run.err, "reloaded " + env.string() + ": cross-fading to the new version\n") == 1, run.err);
  CHECK(run.out.find("(limit 1 N, magnitudes)") != std::string::npos);
  CHECK(run.out.find("  limits           tightened by a reload: max force 2 -> 1 N\n") != std::string::npos);
  CHECK(run.out.find("  reloads          1\n") != std::string::npos);
  // Before the edit the 2 N limit held the spring; at the end the new scene's 1 N does.
  const std::string csv = test::slurp_file(log);
  CHECK(largest_output_N(csv, 0.0) == doctest::Approx(2.0).epsilon(0.01));
  CHECK(largest_output_N(csv, 2.1) <= 1.0 + 1e-9);
}

TEST_CASE("planar run reload: an invalid edit, a 1-DOF file and another profile are each refused once, the scene runs on" *
          doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("planar_reload_refuse");
  const auto env = scratch.write("env.json", spring_env("haplink"));
  std::thread editor([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    scratch.write("env.json", spring_env("haplink", "", "\"200 N\""));  // a force is not a stiffness
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    scratch.write("env.json", R"({"effects": [{"type": "spring", "stiffness": "100 N/m", "center": "0 mm"}]})");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    scratch.write("env.json", spring_env("haply2diy_v3"));
  });
  const test::CliOutcome run = test::run_cli("run " + env.string() + " --duration 1.8s --hand hold --quiet");
  editor.join();
  CHECK(run.exit_code == 0);
  // The located error, once.
  CHECK_MESSAGE(test::occurrences(run.err, "reload failed, keeping the running version: " + env.string() +
                                         ": /effects/0/stiffness: ") == 1,
                run.err);
  CHECK(test::occurrences(run.err, "reload failed") == 1);
  CHECK(test::occurrences(run.err, "reload refused, keeping the running version: " + env.string() +
                                 ": the device cannot change during a run (the file now makes a 1-DOF scene; this "
                                 "run's is 2-DOF (planar))\n") == 1);
  CHECK(test::occurrences(run.err, "reload refused, keeping the running version: " + env.string() +
                                 ": the device cannot change during a run (profile name \"haplink\" -> "
                                 "\"haply2diy_v3\", ") == 1);
  CHECK(run.err.find("reloaded") == std::string::npos);
  CHECK(run.out.find("reloads") == std::string::npos);
  CHECK(run.out.find("on sim:haplink") != std::string::npos);
  CHECK(run.out.find("(limit 2 N, magnitudes)") != std::string::npos);
}
