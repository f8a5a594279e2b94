// Environment test specs: expectations met and unmet, negative specs, invalid specs
// with located errors, and discovery.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "engine/harness/test_spec.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// Writes a spec next to the shipped wall environment's copy in a temporary folder.
std::string write_spec(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "hapscene_specs";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(test::source_path("environments/wall.json"), dir / "wall.json",
                             std::filesystem::copy_options::overwrite_existing);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace

TEST_CASE("spec: unmet expectations fail with what was expected and found") {
  const std::string path = write_spec("wall.test.json", R"({
    "forces": [{"x": "15 mm", "force": "-3 N", "tolerance": "0.1 N"}],
    "zero_outside": ["20 mm", "45 mm"],
    "never_exceeds": "2 N",
    "scenarios": [{"scenario": "release", "min_half_cycles": 3}]})");
  const SpecResult result = run_test_spec(path);
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 4);
  CHECK(result.outcomes[0].message == "force at x 15 mm, v 0 m/s: expected -3 N +/- 0.1 N, got -2.5 N");
  CHECK(result.outcomes[1].what == "/zero_outside");
  CHECK(result.outcomes[1].message.find("no, ") != std::string::npos);
  CHECK(result.outcomes[2].message.find("never exceeds 2 N: largest 4.5") == 0);
  CHECK(result.outcomes[3].message == "release: at least 3 half-cycles, got 0");
  for (const SpecOutcome& o : result.outcomes) CHECK_FALSE(o.pass);
}

TEST_CASE("spec: a negative spec passes when the harness fails the environment") {
  const SpecResult result = run_test_spec(test::source_path("tests/harness/specs/unstable_wall.test.json"));
  CHECK(result.pass);
  CHECK(result.environment_path.ends_with("unstable_wall.json"));
}

TEST_CASE("spec: invalid specs are refused with the place") {
  CHECK(test::input_error_of([] { run_test_spec(write_spec("a.test.json", R"({"environment": "wall.json", "forcez": []})")); })
            .ends_with("a.test.json: /forcez: unknown key \"forcez\" (did you mean \"forces\"?)"));
  CHECK(test::input_error_of([] {
          run_test_spec(write_spec("b.test.json", R"({"environment": "wall.json", "forces": [{"x": "1 N", "force": 0}]})"));
        }).ends_with("b.test.json: /forces/0/x: expected a length (m), got a force (\"1 N\")"));
  CHECK(test::input_error_of([] {
          run_test_spec(write_spec("c.test.json", R"({"environment": "wall.json", "scenarios": [{"scenario": "wobble"}]})"));
        }).find("/scenarios/0/scenario: \"wobble\" is not one of") != std::string::npos);
  CHECK(test::input_error_of([] {
          run_test_spec(write_spec("d.test.json",
                                   R"({"environment": "wall.json", "scenarios": [{"scenario": "press", "fail": ["pasivity"]}]})"));
        }).ends_with("/scenarios/0/fail/0: unknown check \"pasivity\" (did you mean \"passivity\"?)"));
  CHECK(test::input_error_of([] { run_test_spec(write_spec("e.test.json", R"({})")); })
            .ends_with("e.json: cannot open file"));
}
