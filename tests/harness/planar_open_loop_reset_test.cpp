// The 2-D open-loop scan of a script that keeps state: one instance reset() before each
// point gives what fresh instances give when reset() restores the state, so a region
// check over thousands of points needs a handful of creations (the maze's spec, with its
// zero_outside and never_exceeds, stays within the creation budget even when each
// creation is slow); a script whose reset() does not restore its state still gets fresh
// instances at every point.
#include <doctest/doctest.h>

#include <string>

#include "engine/harness/planar_open_loop.hpp"
#include "engine/harness/test_spec.hpp"
#include "engine/load/environment.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// A script with state restored by reset() (a proxy that starts where the handle first is,
// then lags behind it: a stateful field), and a top level that burns about 5 ms of CPU.
const char* kSlowTopResetScript = R"(
needs = { velocity = false, time = false }
local burn = 0
for i = 1, 600000 do burn = burn + i end
local px, started
function reset() px, started = 0, false end
reset()
function force(s)
  if not started then px, started = s.x, true end
  local f = -10 * (s.x - px)
  px = px + 0.5 * (s.x - px)
  return f, 0
end
)";

// State that reset() leaves alone: the count of calls.
const char* kCountingScript = R"(
needs = { velocity = false, time = false }
local calls = 0
function force(s) calls = calls + 1; return calls, 0 end
)";

std::string environment_with(const std::string& script) {
  return R"({"name": "s", "device": "haplink", "effects": [{"type": "script", "file": ")" + script + R"("}]})";
}

}  // namespace

TEST_CASE("planar open loop: a stateful script with reset() is scanned by one reset instance, as fresh ones give") {
  const test::ScratchFolder folder("planar_open_loop_reset");
  folder.write("slow.lua", kSlowTopResetScript);
  const auto env = folder.write("slow.json", environment_with("slow.lua"));
  const PlanarScene scene = load_planar_environment_file(env.string());
  const std::vector<Vec2> grid = planar_workspace_grid(scene, kPlanarFaultScanStep_m);
  REQUIRE(grid.size() == 8436);
  PlanarOpenLoop open_loop(scene);
  // Fresh instances at all 8436 points would take about 40 s of creations, over the 20 s
  // budget: refused before. One reset instance needs a few creations.
  const PlanarOpenLoopScan scan = open_loop.scan(grid, Vec2{});
  CHECK(scan.behaviour.stateful);
  REQUIRE(scan.force_N.size() == grid.size());
  // A fresh instance's first call: the proxy at the handle, no force.
  for (std::size_t i = 0; i < grid.size(); i += 997) {
    CAPTURE(i);
    CHECK(scan.force_N[i][0] == 0.0);
    CHECK(scan.force_N[i][1] == 0.0);
  }
  CHECK(open_loop.faults().empty());

  // The spec with the region checks (zero_outside over the workspace, never_exceeds).
  folder.write("slow.test.json",
               R"({"zero_outside": {"min": ["-1 mm", "100 mm"], "max": ["1 mm", "101 mm"]}, "never_exceeds": "1 N"})");
  const SpecResult result = run_test_spec((folder.dir / "slow.test.json").string());
  CHECK(result.pass);
}

TEST_CASE("planar open loop: state reset() leaves alone still gets fresh instances at every point") {
  const test::ScratchFolder folder("planar_open_loop_noreset");
  folder.write("count.lua", kCountingScript);
  const auto env = folder.write("count.json", environment_with("count.lua"));
  const PlanarScene scene = load_planar_environment_file(env.string());
  const std::vector<Vec2> grid = planar_workspace_grid(scene, 5e-3);
  PlanarOpenLoop open_loop(scene);
  const PlanarOpenLoopScan scan = open_loop.scan(grid, Vec2{});
  CHECK(scan.behaviour.stateful);
  REQUIRE(scan.force_N.size() == grid.size());
  // A fresh instance's first call answers 1 everywhere.
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (scan.force_N[i][0] != 1.0) FAIL_CHECK("point " << i << ": " << scan.force_N[i][0]);
  }
}

TEST_CASE("planar spec: the maze's region checks are back and pass") {
  const SpecResult result = run_test_spec(test::source_path("environments/planar/haplink_maze.test.json"));
  CHECK(result.pass);
  bool zero_outside = false;
  bool never_exceeds = false;
  for (const SpecOutcome& outcome : result.outcomes) {
    zero_outside = zero_outside || (outcome.what == "/zero_outside" && outcome.pass);
    never_exceeds = never_exceeds || (outcome.what == "/never_exceeds" && outcome.pass);
  }
  CHECK(zero_outside);
  CHECK(never_exceeds);
}
