// Test specs for 2-DOF (planar) environments: the shipped ones pass; unmet expectations
// fail with what was expected and found; the forms of the other dimension are refused
// with the place and the form expected; closed-loop expectations are not judged yet and
// fail; script faults at rest and in motion fail a spec with no expectation reaching them.
#include <doctest/doctest.h>

#include <string>

#include "engine/base/errors.hpp"
#include "engine/harness/test_spec.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// The course's solid box on the haplink, as environments/planar/haplink_box_inside.json.
const char* kBoxEnvironment = R"({"name": "box", "device": "haplink", "effects": [
  {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": "200 N/m", "solid": "inside"}]})";

std::string spec_error(const std::string& path) {
  try {
    run_test_spec(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("planar spec: met and unmet expectations say what was expected and found") {
  const test::ScratchFolder folder("planar_spec_unmet");
  folder.write("box.json", kBoxEnvironment);
  const std::string path = folder.write("box.test.json", R"({
    "forces": [{"at": ["-38 mm", "122 mm"], "force": ["-0.4 N", "0 N"], "tolerance": "1e-9 N"},
               {"at": ["-38 mm", "122 mm"], "force": ["-0.1 N", "0.4 N"], "tolerance": "0.4 N"},
               {"at": ["-38 mm", "122 mm"], "v": ["0.1 m/s", "0 m/s"], "force": ["-0.1 N", "0.4 N"], "tolerance": "0.6 N"}],
    "zero_outside": {"min": ["-30 mm", "110 mm"], "max": ["0 mm", "135 mm"]},
    "never_exceeds": "1.5 N"})").string();
  const SpecResult result = run_test_spec(path);
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 5);
  CHECK(result.outcomes[0].pass);
  CHECK(result.outcomes[0].what == "/forces/0");
  // |(-0.4, 0) - (-0.1, 0.4)| = 0.5 N: beyond 0.4 N, within 0.6 N.
  CHECK_FALSE(result.outcomes[1].pass);
  CHECK(result.outcomes[1].message ==
        "force at (-38, 122) mm, v (0, 0) m/s: expected (-0.1, 0.4) N +/- 0.4 N, got (-0.4, 0) N (off by 0.5 N)");
  CHECK(result.outcomes[2].pass);
  CHECK(result.outcomes[3].what == "/zero_outside");
  CHECK_FALSE(result.outcomes[3].pass);
  CHECK(result.outcomes[3].message ==
        "force zero outside the box from (-30, 110) mm to (0, 135) mm (every 1 mm of the workspace): no, "
        "(-0.2, 0) N at (-39, 111) mm, v (0, 0) m/s");
  CHECK(result.outcomes[4].what == "/never_exceeds");
  CHECK_FALSE(result.outcomes[4].pass);
  CHECK(result.outcomes[4].message.find("never exceeds 1.5 N (every 1 mm of the workspace): largest 2 N at ") == 0);
}

TEST_CASE("planar spec: the force is the commanded one, clamped keeping its direction, zero outside the workspace") {
  const test::ScratchFolder folder("planar_spec_clamp");
  folder.write("cage.json", R"({"name": "cage", "device": "haplink", "effects": [
    {"type": "box", "min": ["-55 mm", "100 mm"], "max": ["20 mm", "155 mm"], "stiffness": "200 N/m", "solid": "outside"}]})");
  // At (30, 165) mm the proxy is the corner (20, 155): K (proxy - p) = (-2, -2) N, 2.83 N,
  // commanded at the haplink's 2 N: (-sqrt 2, -sqrt 2). At (-75, 130), outside the workspace: 0.
  const std::string path = folder.write("cage.test.json", R"({"forces": [
    {"at": ["30 mm", "165 mm"], "force": ["-1.41421356237 N", "-1.41421356237 N"], "tolerance": "1e-9 N"},
    {"at": ["-75 mm", "130 mm"], "force": [0, 0]}]})").string();
  const SpecResult result = run_test_spec(path);
  for (const SpecOutcome& o : result.outcomes) {
    CAPTURE(o.message);
    CHECK(o.pass);
  }
  CHECK(result.pass);
}

TEST_CASE("planar spec: a 1-D form in a 2-D spec is refused with its place and the 2-D form") {
  const test::ScratchFolder folder("planar_spec_forms");
  folder.write("box.json", kBoxEnvironment);
  const auto error_of = [&](const std::string& text) {
    return spec_error(folder.write("box.test.json", text).string());
  };
  const std::string spec = (folder.dir / "box.test.json").string();
  CHECK(error_of(R"({"forces": [{"x": "10 mm", "force": "1 N"}]})") ==
        spec + ": /forces/0/x: a 1-D spec's form: this spec's environment is 2-DOF (a planar profile), so a point "
               "is \"at\": [x, y] (lengths in m, or strings with a unit)");
  CHECK(error_of(R"({"forces": [{"at": "10 mm", "force": [0, 0]}]})")
            .starts_with(spec + ": /forces/0/at: expected a 2-D vector [x, y] of lengths in m"));
  CHECK(error_of(R"({"forces": [{"at": [0.01, 0.12], "force": "1 N"}]})")
            .starts_with(spec + ": /forces/0/force: expected a 2-D vector [x, y] of forces in N"));
  CHECK(error_of(R"({"forces": [{"at": [0.01, 0.12], "v": 0.1, "force": [0, 0]}]})")
            .starts_with(spec + ": /forces/0/v: expected a 2-D vector [x, y]"));
  CHECK(error_of(R"({"forces": [{"at": [0.01, "120 N"], "force": [0, 0]}]})").starts_with(spec + ": /forces/0/at/1: "));
  CHECK(error_of(R"({"zero_outside": ["-40 mm", "0 mm"]})") ==
        spec + ": /zero_outside: expected a region {\"min\": [x, y], \"max\": [x, y]} in a 2-D spec, got array "
               "(the 1-D form [a, b])");
  CHECK(error_of(R"({"zero_outside": {"min": [0, 0.2], "max": [0.01, 0.1]}})") ==
        spec + ": /zero_outside/max: must not be below \"min\" on either axis");
  CHECK(error_of(R"({"options": {"start": "4 mm"}})") ==
        spec + ": /options/start: a 1-D spec's form: this spec's environment is 2-DOF, so \"start\" is [x, y]");
  CHECK(error_of(R"({"forcse": []})").starts_with(spec + ": /forcse: "));
  // The environment's own errors, from the spec's "/environment".
  folder.write("broken.json", R"({"name": "b", "device": "haplink", "effects": [{"type": "box", "min": 0.1}]})");
  CHECK(error_of(R"({"environment": "broken.json"})").starts_with(spec + ": /environment: "));
}

// As in 1-D: a start the device cannot take is the spec's error, at its place, whether or
// not the spec runs validate (it was the environment's error in the runs, and unchecked
// without them).
TEST_CASE("planar spec: a free start the linkage cannot reach is refused at /options/start") {
  const test::ScratchFolder folder("planar_spec_start");
  folder.write("box.json", kBoxEnvironment);
  const std::string spec = (folder.dir / "box.test.json").string();
  const auto error_of = [&](const std::string& text) { return spec_error(folder.write("box.test.json", text).string()); };
  for (const std::string& expectations : {std::string(), std::string(R"(, "passes_validate": true)")}) {
    CAPTURE(expectations);
    CHECK(error_of(R"({"options": {"start": ["500 mm", "500 mm"]})" + expectations + "}")
              .starts_with(spec + ": /options/start: the haplink cannot put its handle at (0.5, 0.5) m"));
  }
  // A start it reaches is taken.
  const SpecResult reached = run_test_spec(folder.write("box.test.json", R"({"options": {"start": ["-16 mm", "142 mm"]}})").string());
  CHECK(reached.pass);
}

TEST_CASE("planar spec: a 2-D form in a 1-D spec is refused with its place and the 1-D form") {
  const test::ScratchFolder folder("planar_spec_forms_1d");
  folder.write("wall.json", R"({"name": "w", "effects": [{"type": "wall", "position": "10 mm", "stiffness": "100 N/m"}]})");
  const auto error_of = [&](const std::string& text) {
    return spec_error(folder.write("wall.test.json", text).string());
  };
  const std::string spec = (folder.dir / "wall.test.json").string();
  CHECK(error_of(R"({"forces": [{"at": ["10 mm", "0 mm"], "force": [0, 0]}]})") ==
        spec + ": /forces/0/at: a 2-D spec's form: this spec's environment is 1-DOF, so a point is \"x\": X (a "
               "number in m or a string with a unit)");
  CHECK(error_of(R"({"forces": [{"x": "10 mm", "force": ["1 N", "0 N"]}]})") ==
        spec + ": /forces/0/force: a 2-D spec's form (an array): this spec's environment is 1-DOF, so \"force\" "
               "takes a number in N (or a string with a unit)");
  CHECK(error_of(R"({"options": {"start": ["1 mm", "2 mm"]}})") ==
        spec + ": /options/start: a 2-D spec's form (an array): this spec's environment is 1-DOF, so \"start\" "
               "takes a number in m (or a string with a unit)");
  CHECK(error_of(R"({"zero_outside": {"min": [0, 0], "max": [1, 1]}})") ==
        spec + ": /zero_outside: a 2-D spec's form (an object): this spec's environment is 1-DOF, so "
               "\"zero_outside\" takes [a, b], an interval of lengths");
}

TEST_CASE("planar spec: closed-loop expectations are judged by 2-D validate") {
  const test::ScratchFolder folder("planar_spec_closed_loop");
  folder.write("box.json", kBoxEnvironment);
  const std::string path = folder.write("box.test.json", R"({
    "options": {"hand_stiffness": "300 N/m", "start": ["-16 mm", "142 mm"]},
    "forces": [{"at": ["-20 mm", "140 mm"], "force": [0, 0]}],
    "passes_validate": true,
    "scenarios": [{"scenario": "press", "pass": true, "max_force": "2.5 N"},
                  {"scenario": "release", "fail": ["pop_through"]},
                  {"scenario": "swipe", "pass": true}]})").string();
  const SpecResult result = run_test_spec(path);
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 6);
  CHECK(result.outcomes[0].pass);
  CHECK(result.outcomes[1].what == "/passes_validate");
  CHECK(result.outcomes[1].pass);
  CHECK(result.outcomes[1].message == "passes validate: every check passed");
  CHECK(result.outcomes[2].what == "/scenarios/0/max_force");
  CHECK(result.outcomes[2].pass);
  CHECK(result.outcomes[3].what == "/scenarios/0/pass");
  CHECK(result.outcomes[3].pass);
  // A check expected to fail that passes, and a scenario this scene has nothing for.
  CHECK(result.outcomes[4].what == "/scenarios/1/fail");
  CHECK_FALSE(result.outcomes[4].pass);
  CHECK(result.outcomes[4].message.find("release: check pop_through fails: no, ") == 0);
  CHECK(result.outcomes[5].what == "/scenarios/2");
  CHECK_FALSE(result.outcomes[5].pass);
  CHECK(result.outcomes[5].message == "swipe: not applicable to this environment");
  // 2-D names only, each refused where it is written.
  folder.write("box.test.json", R"({"scenarios": [{"scenario": "line"}]})");
  CHECK(spec_error(path).starts_with(path + ": /scenarios/0/scenario: unknown 2-D scenario \"line\""));
  folder.write("box.test.json", R"({"scenarios": [{"scenario": "press", "fail": ["slip"]}]})");
  CHECK(spec_error(path).starts_with(path + ": /scenarios/0/fail/0: unknown 2-D check \"slip\""));
  // Their keys are still checked.
  folder.write("box.test.json", R"({"scenarios": [{"scenario": "press", "passs": true}]})");
  CHECK(spec_error(path).starts_with(path + ": /scenarios/0/passs: "));
  CHECK(spec_error(path).find("did you mean \"pass\"") != std::string::npos);
  folder.write("box.test.json", R"({"never_exceed": "1 N"})");
  CHECK(spec_error(path).find("did you mean \"never_exceeds\"") != std::string::npos);
}

TEST_CASE("planar spec: script faults anywhere in the workspace fail the spec, at rest and in motion") {
  const test::ScratchFolder folder("planar_spec_faults");
  // Faults at rest in a corner of the workspace no expectation asks about.
  folder.write("corner.lua",
               "needs = {velocity = false, time = false}\n"
               "function force(s)\n"
               "  if s.x > 0.035 and s.y > 0.16 then error('corner') end\n"
               "  return 0, 0\n"
               "end\n");
  folder.write("corner.json", R"({"name": "c", "device": "haplink", "effects": [{"type": "script", "file": "corner.lua"}]})");
  const std::string corner = folder.write("corner.test.json", R"({"forces": [{"at": [0, 0.12], "force": [0, 0]}]})").string();
  SpecResult result = run_test_spec(corner);
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 2);
  CHECK(result.outcomes[0].pass);
  CHECK(result.outcomes[1].what == "/environment");
  CHECK(result.outcomes[1].message.find("script fault: ") == 0);
  CHECK(result.outcomes[1].message.find("corner.lua:3: corner (first at x 36.00 mm, y 161.00 mm, v (0, 0) m/s, t 0 s)") !=
        std::string::npos);
  // Faults only when moving fast along -y.
  folder.write("moving.lua",
               "needs = {velocity = true, time = false}\n"
               "function force(s)\n"
               "  if s.vy < -0.3 then error('too fast') end\n"
               "  return 0, 0\n"
               "end\n");
  folder.write("moving.json", R"({"name": "m", "device": "haplink", "effects": [{"type": "script", "file": "moving.lua"}]})");
  const std::string moving = folder.write("moving.test.json", R"({"forces": [{"at": [0, 0.12], "force": [0, 0]}]})").string();
  result = run_test_spec(moving);
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 2);
  CHECK(result.outcomes[1].message.find("too fast (first at x -70.00 mm, y 90.00 mm, v (0, -0.5) m/s, t 0 s)") !=
        std::string::npos);
}
