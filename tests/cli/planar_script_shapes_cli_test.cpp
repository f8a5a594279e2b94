// `hapscene validate` on scenes of scripts that declare their shapes: the scripted box's
// report lists the same scenarios as the built-in box's (press into 4 edges and 4
// corners); a bad `shapes` entry is a load error naming it (exit 2); a 1-D scene refuses
// a script that declares shapes (exit 2).
#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

namespace {

// The scenario lines of a validate report ("press     pass  10 checks   hand presses ..."),
// without the pass/fail column and the check counts: name and description.
std::string scenario_lines(const std::string& out) {
  std::istringstream in(out);
  std::string line;
  std::string lines;
  for (const char* name : {"sweep ", "press ", "swipe ", "release ", "hold ", "shake ", "free "}) {
    in.clear();
    in.seekg(0);
    while (std::getline(in, line)) {
      if (line.rfind(name, 0) != 0) continue;
      const std::size_t description = line.find("   ", 32);
      lines += std::string(name) + "|" + (description == std::string::npos ? line : line.substr(description)) + "\n";
    }
  }
  return lines;
}

}  // namespace

TEST_CASE("planar script shapes CLI: the scripted box and circle run their built-in twins' scenarios") {
  for (const char* name : {"box_inside", "circle_outside"}) {
    CAPTURE(name);
    const CliOutcome builtin = run_cli(std::string("validate environments/planar/haplink_") + name + ".json");
    const CliOutcome scripted = run_cli(std::string("validate environments/planar/haplink_script_") + name + ".json");
    CHECK(builtin.exit_code == 0);
    CHECK(scripted.exit_code == 0);
    const std::string lines = scenario_lines(scripted.out);
    CHECK(occurrences(lines, "\n") == 7);
    CHECK(lines == scenario_lines(builtin.out));
  }
  const CliOutcome box = run_cli("validate environments/planar/haplink_script_box_inside.json --scenario press");
  CHECK(box.exit_code == 0);
  CHECK(box.out.find("hand presses 4 edge and 4 corner places of 1 shapes") != std::string::npos);
}

TEST_CASE("planar script shapes CLI: a bad entry is a located load error, a 1-D scene refuses shapes") {
  ScratchFolder scratch("planar_script_shapes");
  scratch.write("bad.lua",
                "shapes = { { type = \"box\", min = { \"-40 mm\" }, max = { 0, 0.135 }, solid = \"inside\" } }\n"
                "function force(s) return 0, 0 end\n");
  const auto bad = scratch.write(
      "bad.json", R"({"name": "bad", "device": "haplink", "effects": [{"type": "script", "file": "bad.lua"}]})");
  const CliOutcome load = run_cli("validate '" + bad.string() + "'");
  CHECK(load.exit_code == 2);
  CHECK(load.err.find("bad.json: /effects/0/file: ") != std::string::npos);
  CHECK(load.err.find("bad.lua: shapes[1].min: expected a point {x, y} of two lengths, got a table of 1 entries") !=
        std::string::npos);

  scratch.write("one.lua",
                "shapes = { { type = \"circle\", center = { 0, 0 }, radius = \"5 mm\", solid = \"inside\" } }\n"
                "function force(s) return -100 * s.x end\n");
  const auto one = scratch.write("one.json", R"({"name": "one", "effects": [{"type": "script", "file": "one.lua"}]})");
  for (const std::string command : {"validate", "probe"}) {
    CAPTURE(command);
    const CliOutcome refused = run_cli(command + " '" + one.string() + "'" + (command == "probe" ? " --x 0:0:1mm" : ""));
    CHECK(refused.exit_code == 2);
    CHECK(refused.err.find("one.lua: shapes: this is a 1-D scene, and shapes are for 2-D scripts") != std::string::npos);
  }
}
