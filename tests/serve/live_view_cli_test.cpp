// `hapscene run --ui` through the binary: the address it prints, the summary's line, and
// the option's mistakes refused as invalid input (exit code 2).
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"

namespace hapscene {

TEST_CASE("run --ui: prints a loopback address with a token, and the summary counts the events" * doctest::test_suite("threaded")) {
  const test::CliOutcome run = test::run_cli("run environments/spring.json --ui --duration 0.4s --quiet --no-reload");
  CHECK(run.exit_code == 0);
  CHECK(run.err.find("live view: http://127.0.0.1:") != std::string::npos);
  CHECK(run.err.find("/?token=") != std::string::npos);
  CHECK(run.err.find("warning") == std::string::npos);
  CHECK(run.out.find("  ticks            400 in 0.400 s") != std::string::npos);
  CHECK(run.out.find("  live view        ") != std::string::npos);
  CHECK(run.out.find("0 dropped by slow clients, 0 ticks dropped (ring full)") != std::string::npos);
}

TEST_CASE("run --ui: on another address than loopback it warns" * doctest::test_suite("threaded")) {
  const test::CliOutcome run = test::run_cli("run environments/spring.json --ui 0.0.0.0:0 --duration 0.2s --quiet");
  CHECK(run.exit_code == 0);
  CHECK(run.err.find("warning: the live view listens on 0.0.0.0, not on loopback") != std::string::npos);
  CHECK(run.err.find("live view: http://0.0.0.0:") != std::string::npos);
}

TEST_CASE("run --ui: a bad value, one given twice, several files or --sim-time are invalid input") {
  CHECK(test::run_cli("run environments/spring.json --ui 70000").err ==
        "error: hapscene run: --ui: port must be a whole number in [0, 65535], got \"70000\"\n");
  CHECK(test::run_cli("run environments/spring.json --ui=host.example:1").exit_code == 2);
  CHECK(test::run_cli("run environments/spring.json --ui --ui").err == "error: hapscene run: --ui is given twice\n");
  const test::CliOutcome two = test::run_cli("run environments/spring.json environments/wall.json --ui");
  CHECK(two.exit_code == 2);
  CHECK(two.err.find("--ui takes one environment file") != std::string::npos);
  const test::CliOutcome sim = test::run_cli("run environments/spring.json --ui --sim-time");
  CHECK(sim.exit_code == 2);
  CHECK(sim.err.find("--ui: the live view is for real-time runs (drop --sim-time)") != std::string::npos);
}

}  // namespace hapscene
