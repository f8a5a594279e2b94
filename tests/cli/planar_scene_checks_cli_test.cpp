// The scene checks of 2-D validate as users see them: a 2-D effect that can never act is
// warned about by every command that loads the file (probe, run, validate) and fails
// scene/effects; a script that faults only in a corner of the workspace no scenario
// reaches fails scene/script with its message and the pose of the first fault (exit 1),
// as the 1-D field scan does.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

namespace {

const std::string kDevice = "\"" HAPSCENE_SOURCE_DIR "/environments/devices/haplink.json\"";

}  // namespace

TEST_CASE("planar scene checks cli: an effect that never acts is warned about by probe, run and validate") {
  const ScratchFolder folder("planar_scene_checks_inert");
  const auto env = folder.write("inert.json", R"({"device": )" + kDevice + R"(, "effects": [
    {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": "200 N/m", "solid": "inside"},
    {"type": "circle", "center": [-15, 130], "radius": 10, "stiffness": "200 N/m", "solid": "inside"}]})");
  const std::string warning = "warning: " + env.string() +
                              ": /effects/1 (circle): the solid disc of radius 10 m about (-15, 130) m lies wholly "
                              "outside the workspace [-0.07, 0.04] x [0.09, 0.165] m, so the circle never acts; did you "
                              "mean \"center\": [\"-15 mm\", \"130 mm\"], \"radius\": \"10 mm\"?\n";
  const CliOutcome probe = run_cli("probe '" + env.string() + "' --x -20mm:-20mm:1mm --y 120mm:120mm:1mm");
  CHECK(probe.exit_code == 0);
  CHECK(probe.err == warning);
  const CliOutcome run = run_cli("run '" + env.string() + "' --sim-time --duration 0.05s --hand none");
  CHECK(run.exit_code == 0);
  CHECK(occurrences(run.err, warning) == 1);
  const CliOutcome validate = run_cli("validate '" + env.string() + "' --scenario hold");
  CHECK(validate.exit_code == 1);
  CHECK(occurrences(validate.err, warning) == 1);
  CHECK(validate.out.find("effects") != std::string::npos);
  CHECK(validate.out.find("/effects/1 (circle): the solid disc") != std::string::npos);
}

TEST_CASE("planar scene checks cli: a script fault in a corner no scenario reaches fails validate") {
  const ScratchFolder folder("planar_scene_checks_corner");
  folder.write("corner.lua", R"(needs = { velocity = false, time = false }
function force(s)
  if s.x > 0.038 and s.y > 0.16 then error('corner') end
  return 0, 0
end
)");
  const auto env = folder.write("corner.json", R"({"device": )" + kDevice + R"(, "effects": [
    {"type": "script", "file": "corner.lua"}]})");
  const CliOutcome out = run_cli("validate '" + env.string() + "'");
  CHECK(out.exit_code == 1);
  CHECK(out.out.find("script") != std::string::npos);
  CHECK(out.out.find("in the open-loop scan (every 1 mm of the workspace, at rest): ") != std::string::npos);
  CHECK(out.out.find("corner.lua:3: corner (first at x 39.00 mm, y 161.00 mm, v (0, 0) m/s, t 0 s)") != std::string::npos);
  // The scenarios themselves never go there: only the scene's check fails.
  CHECK(out.out.find("scene     FAIL  1 of 1 checks failed") != std::string::npos);
  CHECK(out.out.find("result: FAIL (1 of 47 checks failed: scene/script; 5 not judged)") != std::string::npos);
  const CliOutcome quiet = run_cli("validate --quiet '" + env.string() + "'");
  CHECK(quiet.exit_code == 1);
  CHECK(quiet.out.find("scene/script") != std::string::npos);
}
