// `hapscene run` with hot reload, attacked through the files it watches: the run keeps
// its device and limits, and it ends on time whatever a reload's load does.
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// The largest force the summary says was commanded.
double commanded_N(const std::string& out) {
  std::smatch match;
  REQUIRE(std::regex_search(out, match, std::regex(R"(commanded ([0-9.]+) N \(limit ([0-9.]+) N\))")));
  return std::stod(match[1]);
}

}  // namespace

TEST_CASE("run: a reload pointing the device at a looser profile of the same name is refused mid-run" * doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("run_profile");
  std::string profile = test::slurp_file(test::source_path("environments/devices/hapkit3.json"));
  scratch.write("a/hapkit3.json", profile);
  profile = std::regex_replace(profile, std::regex(R"("max_force": "6 N")"), R"("max_force": "60 N")");
  profile = std::regex_replace(profile, std::regex(R"("slew_limit": "4 N/ms")"), R"("slew_limit": "8 N/ms")");
  scratch.write("b/hapkit3.json", profile);
  // A spring asking for about 400 N at a handle held stiffly near 0 mm: the 6 N limit
  // is what the hand feels (before this was refused, 60 N was commanded).
  const std::string effects = R"("effects": [{"type": "spring", "stiffness": "10 N/mm", "center": "40 mm"}])";
  const auto env = scratch.write("env.json", R"({"device": "a/hapkit3.json", )" + effects + "}");
  std::thread attacker([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    scratch.write("env.json", R"({"device": "b/hapkit3.json", )" + effects + "}");
  });
  const test::CliOutcome run = test::run_cli("run " + env.string() + " --duration 1.5s --hand hold --hand-stiffness 20000 --quiet");
  attacker.join();
  CHECK_MESSAGE(run.err.find("reload refused, keeping the running version: " + env.string() +
                             ": the device cannot change during a run (profile limits.max_force_N 6 -> 60") !=
                    std::string::npos,
                run.err);
  CHECK(commanded_N(run.out) == doctest::Approx(6.0));
  CHECK(run.out.find("(limit 6 N)") != std::string::npos);
  CHECK(run.out.find("reloads") == std::string::npos);
}

TEST_CASE("run: a reload tightening the force limit is taken, and the summary reports the limit in force" * doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("run_tighten");
  const std::string effects = R"("effects": [{"type": "spring", "stiffness": "10 N/mm", "center": "10 mm"}])";
  const auto env = scratch.write("env.json", "{" + effects + "}");
  std::thread editor([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    scratch.write("env.json", R"({"safety": {"max_force": "2 N"}, )" + effects + "}");
  });
  const test::CliOutcome run = test::run_cli("run " + env.string() + " --duration 2s --hand hold --quiet");
  editor.join();
  CHECK_MESSAGE(run.err.find("reloaded " + env.string()) != std::string::npos, run.err);
  CHECK(run.out.find("(limit 2 N)") != std::string::npos);
  CHECK(run.out.find("  limits           tightened by a reload: max force 6 -> 2 N\n") != std::string::npos);
  CHECK(run.out.find("  reloads          1\n") != std::string::npos);
}

TEST_CASE("run: a reload whose load does not end does not hold the run past its duration" * doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("run_hang");
  scratch.write("field.lua", "function force(s) return 0 end\n");
  const auto env = scratch.write(
      "env.json", R"({"effects": [{"type": "script", "file": "field.lua", "limits": {"instructions_at_load": 1000000000}}]})");
  std::thread editor([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    scratch.write("field.lua", "local n = 0\nwhile true do n = n + 1 end\nfunction force(s) return 0 end\n");
  });
  const auto started = std::chrono::steady_clock::now();
  const test::CliOutcome run = test::run_cli("run " + env.string() + " --duration 1s --hand none --quiet");
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;
  editor.join();
  // The load runs about 10^9 VM instructions twice (seconds); the run ends after its 1 s.
  CHECK(took.count() < 3.0);
  CHECK_MESSAGE((run.err.find("abandoned, keeping the running version: the run ended while it was still loading") !=
                     std::string::npos ||
                 run.err.find("reload failed") != std::string::npos),
                run.err);
  CHECK(run.out.find("ticks") != std::string::npos);
}
