// `hapscene validate`, `test` and `plot` as users call them: tables, reports, figures
// and exit codes (0 pass, 1 fail, 2 invalid input).
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_support.hpp"

using hapscene::test::run_cli;
using hapscene::test::slurp_file;

TEST_CASE("cli: validate passes the lab wall and writes a JSON report") {
  const auto report = std::filesystem::temp_directory_path() / "hapscene_report_test.json";
  const auto outcome = run_cli("validate environments/wall.json --report " + report.string());
  CHECK(outcome.exit_code == 0);
  CHECK(outcome.out.find("validate wall (environments/wall.json): 1000 Hz, passivity bound 2b/T = 800 N/m") == 0);
  // Three passivity checks see too little energy to weigh: said, not counted as passes.
  CHECK(outcome.out.find("result: pass (60 checks, 3 not judged)") != std::string::npos);
  const nlohmann::json json = nlohmann::json::parse(slurp_file(report));
  std::filesystem::remove(report);
  CHECK(json["schema"] == "hapscene-validate/2");
  CHECK(json["pass"] == true);
  CHECK(json["scene"]["passivity_bound_N_per_m"] == 800.0);
  REQUIRE(json["scenarios"].size() == 6);
  CHECK(json["scenarios"][1]["name"] == "press");
  CHECK(json["scenarios"][1]["checks"][0]["name"] == "max_force");
  CHECK(json["scenarios"][1]["metrics"]["passivity"]["ratio"].get<double>() < 1.0);
}

TEST_CASE("cli: validate fails a wall at 3x the bound with exit code 1, naming the check") {
  const auto outcome = run_cli("validate tests/harness/specs/unstable_wall.json --scenario press");
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.out.find("passivity      3.0") != std::string::npos);
  CHECK(outcome.out.find("FAIL") != std::string::npos);
  CHECK(outcome.out.find("result: FAIL (1 of 9 checks failed: press/passivity)") != std::string::npos);
}

TEST_CASE("cli: validate refuses invalid input with exit code 2") {
  const auto unknown = run_cli("validate environments/wall.json --scenario wobble");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err ==
        "error: hapscene validate: --scenario: unknown scenario \"wobble\" (one of sweep, press, release, hold, "
        "shake, free; did you mean \"hold\"?)\n");
  CHECK(run_cli("validate environments/wall.json --scenario sweeep").err.find("did you mean \"sweep\"?") !=
        std::string::npos);
  CHECK(run_cli("validate").exit_code == 2);
  CHECK(run_cli("validate environments/nope.json").err == "error: environments/nope.json: cannot open file\n");
  CHECK(run_cli("validate environments/wall.json --hand-stiffness 0").exit_code == 2);
  CHECK(run_cli("validate environments/wall.json environments/spring.json --report x.json").err ==
        "error: hapscene validate: --report and --plot take one environment file\n");
  CHECK(run_cli("validate environments/wall.json --report /nonexistent/dir/r.json").err ==
        "error: hapscene validate: --report /nonexistent/dir/r.json: no folder /nonexistent/dir\n");
}

// The one test that runs every shipped spec (1-D and 2-D, environments and scripts), as
// users and CI run them: without arguments, from the repository's folder.
TEST_CASE("cli: test runs every spec in the repository, or the ones given" * doctest::test_suite("sweeps")) {
  std::size_t shipped = 0;
  for (const char* folder : {"environments", "scripts"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(HAPSCENE_SOURCE_DIR "/" + std::string(folder))) {
      if (entry.path().filename().string().ends_with(".test.json")) ++shipped;
    }
  }
  CHECK(shipped >= 40);
  const auto all = run_cli("test");
  CAPTURE(all.err);
  CHECK(all.exit_code == 0);
  for (const char* spec : {"environments/wall.test.json", "environments/planar/haplink_maze.test.json",
                           "environments/planar/haply2diy_v3_box_outside.test.json", "scripts/planar/maze.test.json",
                           "scripts/planar/mass_spring.test.json"}) {
    CAPTURE(spec);
    CHECK(all.out.find(std::string("PASS ") + spec) != std::string::npos);
  }
  CHECK(all.out.find(std::to_string(shipped) + " specs, ") != std::string::npos);
  CHECK(all.out.find(": all pass\n") != std::string::npos);
  const auto negative = run_cli("test tests/harness/specs/unstable_wall.test.json");
  CHECK(negative.exit_code == 0);

  // A spec the environment does not meet: exit 1 with the unmet expectation.
  const auto dir = std::filesystem::temp_directory_path() / "hapscene_cli_specs";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(HAPSCENE_SOURCE_DIR "/environments/spring.json", dir / "spring.json",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "spring.test.json") << R"({"scenarios": [{"scenario": "release", "min_half_cycles": 30}]})";
  const auto failing = run_cli("test " + (dir / "spring.test.json").string());
  CHECK(failing.exit_code == 1);
  CHECK(failing.out.find("  FAIL /scenarios/0/min_half_cycles: release: at least 30 half-cycles, got 3") !=
        std::string::npos);
  std::ofstream(dir / "bad.test.json") << R"({"environment": "spring.json", "never_exceeds": "-1 N"})";
  const auto invalid = run_cli("test " + (dir / "bad.test.json").string());
  CHECK(invalid.exit_code == 2);
  CHECK(invalid.err.ends_with("bad.test.json: /never_exceeds: must be > 0, got -1 N\n"));
}

TEST_CASE("cli: plot and --plot write SVG figures with axes, units and the limit" * doctest::test_suite("threaded")) {
  const auto svg = std::filesystem::temp_directory_path() / "hapscene_plot_test.svg";
  const auto plot = run_cli("plot environments/texture.json --scenario shake --output " + svg.string());
  CHECK(plot.exit_code == 0);
  const std::string text = slurp_file(svg);
  CHECK(text.starts_with("<?xml"));
  CHECK(text.find("<svg xmlns=\"http://www.w3.org/2000/svg\"") != std::string::npos);
  for (const char* label : {"handle position x (mm)", "force (N)", "time t (s)", "velocity v (m/s)",
                            "safety limit +/-6 N", "v = 0.1 m/s", "v = -0.05 m/s", "shake (hand shakes"}) {
    CAPTURE(label);
    CHECK(text.find(label) != std::string::npos);
  }
  CHECK(text.ends_with("</svg>\n"));
  std::filesystem::remove(svg);

  CHECK(run_cli("validate environments/wall.json --scenario hold --plot " + svg.string()).exit_code == 0);
  CHECK(slurp_file(svg).find("hold (hand holds still") != std::string::npos);
  std::filesystem::remove(svg);
  const auto log = std::filesystem::temp_directory_path() / "hapscene_run_log.csv";
  const auto run = run_cli("run environments/wall.json --sim-time --duration 0.5s --log " + log.string() +
                           " --plot " + svg.string());
  CHECK(run.exit_code == 0);
  CHECK(run.out.find("  telemetry        500 samples written to") != std::string::npos);
  CHECK(slurp_file(log).starts_with("t_s,x_m,v_m_per_s,force_N,output_N,duty,direction\n0,"));
  CHECK(slurp_file(svg).find("position: run, hand sweep") != std::string::npos);
  std::filesystem::remove(svg);
  std::filesystem::remove(log);
}
