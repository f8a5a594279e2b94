// `validate` prints a line per scenario and the rows of only the checks that failed;
// --verbose prints every check.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"

using namespace hapscene::test;

TEST_CASE("cli: validate summarises by default, --verbose shows every check" * doctest::test_suite("threaded")) {
  const CliOutcome summary = run_cli("validate environments/wall.json");
  CAPTURE(summary.out);
  CHECK(summary.exit_code == 0);
  CHECK(summary.out.starts_with("validate wall (environments/wall.json): 1000 Hz"));
  CHECK(summary.out.find("\nsweep     pass  9 checks                  hand sweeps ") != std::string::npos);
  CHECK(summary.out.find("\nhold      pass  11 checks, 1 not judged   hand holds still at 12 mm\n") != std::string::npos);
  CHECK(summary.out.find("          passivity      ") == std::string::npos);  // no check rows when all pass
  CHECK(summary.out.ends_with("\nresult: pass (60 checks, 3 not judged)\n"));
  CHECK(occurrences(summary.out, "\n") == 11);

  const CliOutcome verbose = run_cli("validate environments/wall.json --verbose");
  CHECK(verbose.exit_code == 0);
  CHECK(verbose.out.find("scenario  check          value           threshold        verdict  detail\n") != std::string::npos);
  CHECK(occurrences(verbose.out, "          passivity      ") == 6);

  // A failure: its scenario line says so and the failed check's row follows it.
  const CliOutcome failing = run_cli("validate tests/harness/specs/unstable_wall.json --scenario press");
  CAPTURE(failing.out);
  CHECK(failing.exit_code == 1);
  CHECK(failing.out.find("\npress     FAIL  ") != std::string::npos);
  CHECK(failing.out.find(" checks failed") != std::string::npos);
  CHECK(failing.out.find("FAIL     ") != std::string::npos);  // the failed row, as the table shows it
  CHECK(run_cli("validate environments/wall.json --verbose --quiet").exit_code == 2);
}
