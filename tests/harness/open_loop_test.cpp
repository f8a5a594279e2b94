// Open-loop evaluation: every point as fresh script instances give it (independent of
// the order of the points), faults recorded once with file:line, and scripts with state
// or time never read as a fixed field (no invented walls).
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/harness/open_loop.hpp"
#include "engine/harness/validate.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

std::string script_scene(const std::string& source) {
  nlohmann::json root = {{"effects", nlohmann::json::array({{{"type", "script"}, {"source", source}}})}};
  return root.dump();
}

std::vector<double> grid(double from_m, double to_m, double step_m) {
  std::vector<double> x;
  for (double v = from_m; step_m > 0 ? v <= to_m + 1e-12 : v >= to_m - 1e-12; v += step_m) x.push_back(v);
  return x;
}

// A virtual mass on a coupling spring, integrated per call: state.
const char* kMass = R"(
needs = { velocity = false, time = false }
local xm, started
function reset() xm, started = 0, false end
reset()
function force(s)
  if not started then xm, started = s.x, true end
  xm = xm + 0.5 * (s.x - xm)
  return -2000 * (s.x - xm)
end)";

}  // namespace

TEST_CASE("open loop: a stateful script gives the same force at a point whatever was probed before") {
  const Scene scene = scene_from(script_scene(kMass));
  const std::vector<double> up = grid(-0.02, 0.02, 0.001);
  std::vector<double> down = up;
  std::reverse(down.begin(), down.end());
  OpenLoop a(scene);
  OpenLoop b(scene);
  const OpenLoopScan scan_up = a.scan(up, 0.0);
  const OpenLoopScan scan_down = b.scan(down, 0.0);
  CHECK(scan_up.behaviour.stateful);
  REQUIRE(scan_up.force_N.size() == up.size());
  for (std::size_t i = 0; i < up.size(); ++i) {
    CHECK(scan_up.force_N[i] == scan_down.force_N[up.size() - 1 - i]);
    // The same as a fresh instance asked about this point alone.
    OpenLoop single(scene);
    CHECK(scan_up.force_N[i] == single.force_N(up[i], 0.0));
  }
  // From fresh instances the mass starts where the handle is: 0 N everywhere.
  CHECK(std::all_of(scan_up.force_N.begin(), scan_up.force_N.end(), [](double f) { return f == 0.0; }));
}

TEST_CASE("open loop: a fault is recorded once with file:line, and later points are still evaluated") {
  const Scene scene = scene_from(script_scene(
      "needs = {velocity = false, time = false}\n"
      "function force(s)\n  if s.x > 0.01 then return k * s.x end\n  return -100 * s.x\nend"));
  OpenLoop open_loop(scene);
  const std::vector<double> x = grid(0.02, -0.02, -0.005);  // downwards: the fault comes first
  const OpenLoopScan scan = open_loop.scan(x, 0.0);
  REQUIRE(open_loop.faults().lines().size() == 1);
  // The lowest point that raised it, whatever the order of the points.
  CHECK(open_loop.faults().lines()[0] ==
        "test.json#/effects/0/source:3: undefined global 'k' (first at x 15.00 mm, v 0 m/s, t 0 s)");
  // Points below the fault are not silenced by it.
  CHECK(scan.force_N.back() == doctest::Approx(2.0));
  CHECK(scan.force_N[3] == doctest::Approx(-0.5));  // x = 5 mm
}

TEST_CASE("open loop: a script that reads time is not a fixed field, t selects the instant") {
  const Scene scene = scene_from(script_scene("function force(s) return math.sin(2 * math.pi * 80 * s.t) end"));
  OpenLoop at_zero(scene);
  const OpenLoopScan scan = at_zero.scan(grid(-0.01, 0.01, 0.005), 0.0);
  CHECK(scan.behaviour.time_varying);
  CHECK_FALSE(scan.behaviour.stateful);
  CHECK(scan.force_N[0] == 0.0);
  OpenLoop later(scene, 0.003125);  // a quarter period
  CHECK(later.force_N(0.0, 0.0) == doctest::Approx(1.0));
}

TEST_CASE("open loop: a pure script and built-in effects are a fixed field") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100},
    {"type": "script", "source": "function force(s) return -50 * s.x end"}]})");
  OpenLoop open_loop(scene);
  const OpenLoopScan scan = open_loop.scan(grid(-0.01, 0.01, 0.001), 0.0);
  CHECK(scan.behaviour.static_field());
  CHECK(scan.force_N[0] == doctest::Approx(1.5));
  CHECK(open_loop.faults().empty());
}

TEST_CASE("force field: no walls are inferred from a script with state, nor from one with time") {
  // One instance swept across the workspace lags (the mass follows), which a scan without
  // fresh instances reads as a stiff region everywhere.
  const Scene mass = scene_from(script_scene(kMass));
  const ForceField field = probe_force_field(mass, ValidateThresholds{}.stiff_threshold_N_per_m);
  CHECK(field.regions.empty());
  CHECK(field.behaviour.stateful);
  CHECK(field.behaviour.note == "test.json#/effects/0/source keeps state between calls: not a fixed force field");
  const Scene buzz = scene_from(script_scene(
      "function force(s) if s.x > 0.01 then return -5000 * (s.x - 0.01) * math.cos(s.t * 50) end return 0 end"));
  const ForceField buzz_field = probe_force_field(buzz, ValidateThresholds{}.stiff_threshold_N_per_m);
  CHECK(buzz_field.behaviour.time_varying);
  CHECK(buzz_field.regions.empty());
  // The same wall without time is a wall.
  const Scene wall = scene_from(script_scene(
      "needs = {time = false}\nfunction force(s) if s.x > 0.01 then return -5000 * (s.x - 0.01) end return 0 end"));
  CHECK(probe_force_field(wall, ValidateThresholds{}.stiff_threshold_N_per_m).regions.size() == 1);
}

TEST_CASE("force field: a workspace too wide to sample is refused, naming the file") {
  Scene scene = scene_from(R"({"effects": []})");
  scene.safety.workspace_min_m = -1000.0;
  scene.safety.workspace_max_m = 1000.0;
  const std::string message = test::input_error_of([&] { probe_force_field(scene, 200.0); });
  CHECK(message.starts_with("test.json: /device: hapkit3: the workspace [-1000, 1000] m spans 2000 m"));
  CHECK(message.find("at most 1 m") != std::string::npos);
}
