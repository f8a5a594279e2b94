// The command line on 2-DOF environments with script effects: probe of a scripted twin
// prints the built-in's grid to the byte; probe and run report a script's fault once and
// exit 1; a script of the other dimension is a load error (exit 2) that says so.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

namespace {

// A planar environment on the haplink with one inline script effect.
std::string planar_env(const std::string& source) {
  return R"({"name": "t", "device": "haplink", "effects": [{"type": "script", "source": ")" + source + R"("}]})";
}

}  // namespace

TEST_CASE("planar script probe: the scripted twins print the built-ins' grids byte for byte") {
  const std::string grid = " --x -70mm:40mm:2.5mm --y 90mm:165mm:2.5mm";
  for (const char* name : {"box_inside", "box_outside", "circle_inside", "circle_outside"}) {
    CAPTURE(name);
    const CliOutcome builtin = run_cli(std::string("probe environments/planar/haplink_") + name + ".json" + grid);
    const CliOutcome scripted =
        run_cli(std::string("probe environments/planar/haplink_script_") + name + ".json" + grid);
    REQUIRE(builtin.exit_code == 0);
    REQUIRE(scripted.exit_code == 0);
    CHECK(scripted.err.empty());
    CHECK(scripted.out == builtin.out);
    CHECK(builtin.out.size() > 1000);
  }
}

TEST_CASE("planar script probe and run: every shipped 2-D script environment probes and runs clean") {
  for (const char* name : {"bumps", "mass_spring", "vortex", "magnet"}) {
    CAPTURE(name);
    const CliOutcome probe =
        run_cli(std::string("probe environments/planar/haplink_") + name + ".json --x -30mm:0mm:5mm --y 127mm:127mm:1mm");
    CHECK(probe.exit_code == 0);
    // A script that keeps state is noted, as the 1-D probe notes it.
    if (std::string(name) == "mass_spring") {
      CHECK(probe.err ==
            "note: scripts/planar/mass_spring.lua keeps state between calls: not a fixed force field; each point is "
            "from fresh instances at t = 0 s\n");
    } else {
      CHECK(probe.err.empty());
    }
    const CliOutcome run =
        run_cli(std::string("run environments/planar/haplink_") + name + ".json --sim-time --duration 1s --hand circle");
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("script ok") != std::string::npos);
  }
}

TEST_CASE("planar script probe: a fault is reported once with the first point that met it, exit 1") {
  ScratchFolder scratch("planar_script_probe");
  const auto env = scratch.write(
      "env.json", planar_env("function force(s) if s.x > 0.01 then return 0/0, 1 end return 0.5, 0.25 end"));
  const CliOutcome probe = run_cli("probe '" + env.string() + "' --x 0mm:30mm:10mm --y 120mm:130mm:10mm");
  CHECK(probe.exit_code == 1);
  // Every point from fresh instances: the points before the fault keep their force.
  CHECK(probe.out.find("0,0.12,0,0,0.5,0.25,") != std::string::npos);
  CHECK(probe.out.find("\n0.02,0.12,0,0,,,,\n") != std::string::npos);  // faulted: empty, not 0 N
  CHECK(probe.err.find("force(s) returned nan, 1, expected two finite numbers fx, fy (N) (first at x 20.00 mm, "
                       "y 120.00 mm, v (0, 0) m/s, t 0 s)") != std::string::npos);
  // Once, though four points met it.
  CHECK(probe.err.find("returned nan") == probe.err.rfind("returned nan"));
}

TEST_CASE("planar script run: a script that faults is switched off, reported, and the run exits 1") {
  ScratchFolder scratch("planar_script_run");
  const auto env = scratch.write(
      "env.json", planar_env("function force(s) if s.t > 0.2 then error('broke') end return 0, 0 end"));
  const CliOutcome run = run_cli("run '" + env.string() + "' --sim-time --duration 0.5s");
  CHECK(run.exit_code == 1);
  CHECK(run.out.find("script disabled  ") != std::string::npos);
  CHECK(run.out.find(":1: broke (at t = 0.2") != std::string::npos);
}

TEST_CASE("planar script CLI: a script of the other dimension is a load error, exit 2") {
  ScratchFolder scratch("planar_script_dimension");
  const auto env = scratch.write("env.json", planar_env("function force(s) return -100 * s.x end"));
  const CliOutcome probe = run_cli("probe '" + env.string() + "' --x 0:0:1mm --y 120mm:120mm:1mm");
  CHECK(probe.exit_code == 2);
  CHECK(probe.err.find("force(s) returned one number, expected two, fx, fy (N): this is a 2-D scene, and a 1-D "
                       "script returns one") != std::string::npos);
  // A 2-D script given alone runs as a 1-D (Hapkit) environment, and says why it cannot.
  const CliOutcome alone = run_cli("probe scripts/planar/box.lua --x 0:0:1mm");
  CHECK(alone.exit_code == 2);
  CHECK(alone.err.find("s.y is only in 2-D scenes, and this is a 1-D scene") != std::string::npos);
}
