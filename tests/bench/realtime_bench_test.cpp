// `hapscene bench --realtime`: the tick paced as the real loop runs it, reported beside
// the hot figures, with the build named and the goals' verdicts (no timing is checked).
#include <doctest/doctest.h>

#include "tests/cli/cli_support.hpp"

namespace hapscene {
namespace {

TEST_CASE("bench --realtime prints hot, cold and warm figures and the goals" * doctest::test_suite("threaded")) {
  const test::CliOutcome outcome = test::run_cli("bench --realtime --seconds 0.05 environments/spring.json");
  CHECK(outcome.exit_code == 0);
  const std::string& out = outcome.out;
  CHECK(out.find("build: ") == 0);
  CHECK(out.find("hot_p50  hot_p99  cold_p50  cold_p99  warm_p50  warm_p99") != std::string::npos);
  CHECK(out.find("spring     built-in (JSON)") != std::string::npos);
  CHECK(out.find("spring     Lua script") != std::string::npos);
  CHECK(out.find("spring built-in: warm p50 ") != std::string::npos);
  CHECK(out.find("spring Lua: warm p50 ") != std::string::npos);
}

}  // namespace
}  // namespace hapscene
