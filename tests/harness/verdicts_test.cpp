// Verdicts that must not hide anything: "not judged" is said, failing slip and jitter
// checks say where and when, effects that never act and faults met open loop fail scene
// checks, and `--quiet`'s line carries the verdict.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/harness/report.hpp"
#include "engine/harness/validate.hpp"
#include "tests/support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

const CheckResult& check(const ScenarioResult& result, const std::string& name) {
  const auto found = std::find_if(result.checks.begin(), result.checks.end(),
                                  [&](const CheckResult& c) { return c.name == name; });
  REQUIRE(found != result.checks.end());
  return *found;
}

}  // namespace

TEST_CASE("verdicts: passivity below the judged energy is 'not judged', neither pass nor fail") {
  // A damper only absorbs energy: created is negative, so the ratio is too.
  const Scene scene = scene_from(R"({"effects": [{"type": "damper", "damping": "2 N*s/m"}]})");
  const ValidationReport report = validate_scene(scene, {ScenarioKind::sweep}, {});
  const CheckResult& passivity = check(report.scenarios[0], "passivity");
  CHECK(passivity.value < 0.0);
  CHECK_FALSE(passivity.judged);
  CHECK(passivity.pass);  // it does not fail the run
  CHECK(std::string(verdict_text(passivity)) == "not judged");
  CHECK(passivity.detail.ends_with("; not judged: created at most 0.01 mJ"));
  const std::string table = format_report_table(report);
  CHECK(table.find("not judged created") != std::string::npos);
  CHECK(table.find("result: pass (8 checks, 1 not judged)") != std::string::npos);
  CHECK(report_to_json(report)["scenarios"][0]["checks"][4]["verdict"] == "not judged");
  CHECK(format_report_line(report) == "PASS test (test.json): 8 checks, 1 not judged\n");
}

TEST_CASE("verdicts: failing slip and jitter checks say where and when") {
  // 4 N switched on and off every 50 ms from 0.125 s: steps above the 2 N slip step.
  const Environment environment = test::environment_from(R"({"effects": [{"type": "script", "source":
    "function force(s) if s.t > 0.125 and math.floor(s.t / 0.05) % 2 == 1 then return 4 end return 0 end"}],
    "validate": {"max_force_jitter": "0.01 N"}})");
  const ValidationReport report =
      validate_scene(environment.scene, {ScenarioKind::hold}, {.thresholds = environment.validate});
  const CheckResult& slip = check(report.scenarios[0], "slip");
  REQUIRE_FALSE(slip.pass);
  CHECK(slip.detail.find("; first at ") != std::string::npos);
  CHECK(slip.detail.find(", t 0.15") != std::string::npos);
  const CheckResult& jitter = check(report.scenarios[0], "jitter");
  REQUIRE_FALSE(jitter.pass);
  CHECK(jitter.detail.find("; largest ") != std::string::npos);
  CHECK(jitter.detail.find(" mm, t ") != std::string::npos);
  const nlohmann::json metrics = report_to_json(report)["scenarios"][0]["metrics"];
  CHECK(metrics["slip_first_t_s"].get<double>() == doctest::Approx(0.15).epsilon(0.01));
  CHECK(metrics["jitter_peak_N"].get<double>() > 1.0);
}

TEST_CASE("verdicts: a wall that never acts fails the scene's effects check") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100},
    {"type": "wall", "position": 20, "stiffness": "500 N/m", "solid": "above"}]})");
  const ValidationReport report = validate_scene(scene, {ScenarioKind::hold}, {});
  CHECK_FALSE(report.pass);
  REQUIRE(report.scene_checks.size() == 1);
  CHECK(report.scene_checks[0].name == "effects");
  CHECK(report.scene_checks[0].detail.find("test.json: /effects/1 (wall)") == 0);
  CHECK(format_report_line(report).starts_with("FAIL test (test.json): 1 of 11 checks failed: scene/effects"));
  const nlohmann::json json = report_to_json(report);
  CHECK(json["scene_checks"][0]["verdict"] == "FAIL");  // the table's word
  CHECK(json["scene"]["load_warnings"].size() == 1);
}

TEST_CASE("verdicts: a script fault met only by the open-loop scan fails the scene's script check") {
  // Faults only beyond 40 mm, where no scenario takes the handle with the default hand.
  const Scene scene = scene_from(R"({"effects": [{"type": "script", "source":
    "needs = {time = false, velocity = false}\nfunction force(s)\n  if s.x > 0.044 then error('too far') end\n  return 0\nend"}]})");
  const ValidationReport report = validate_scene(scene, {ScenarioKind::hold}, {});
  CHECK_FALSE(report.pass);
  REQUIRE(report.scene_checks.size() == 1);
  CHECK(report.scene_checks[0].name == "script");
  CHECK(report.scene_checks[0].detail.starts_with(
      "in the force-field scan: test.json#/effects/0/source:3: too far (first at x 44.0"));
  const nlohmann::json json = report_to_json(report);
  CHECK(json["scene"]["field_script_faults"].size() == 1);
}

TEST_CASE("verdicts: a valid scene's report has no scene checks and a fixed field") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  const ValidationReport report = validate_scene(scene, {ScenarioKind::hold}, {});
  CHECK(report.scene_checks.empty());
  CHECK(report.field.behaviour.static_field());
  CHECK(report_to_json(report)["scene"]["static_field"] == true);
}

}  // namespace HAPSCENE_TEST_FILE
