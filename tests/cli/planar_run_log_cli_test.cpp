// Script log() lines in a 2-DOF run: printed on stderr exactly as a 1-DOF run prints them
// ("FILE:LINE: text (t = T s)", escaped), each once, after the run when stderr is not a
// terminal.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

TEST_CASE("planar run log: a 2-D script's log() lines print as a 1-D script's do, once each") {
  ScratchFolder scratch("planar_run_log");
  // The same log calls, in a 1-D and a 2-D script: at 0.1 s and at 0.25 s.
  const std::string logs = "  if s.t > 0.0995 and s.t < 0.1005 then log('first') end\n"
                           "  if s.t > 0.2495 and s.t < 0.2505 then log('second\\nline') end\n";
  const auto flat = scratch.write("flat.lua", "function force(s)\n" + logs + "  return 0\nend\n");
  const auto planar_script = scratch.write("planar.lua", "function force(s)\n" + logs + "  return 0, 0\nend\n");
  const auto planar = scratch.write(
      "planar.json", R"({"name": "t", "device": "haplink", "effects": [{"type": "script", "file": "planar.lua"}]})");
  const CliOutcome one = run_cli("run '" + flat.string() + "' --sim-time --duration 0.4s --hand none --quiet");
  const CliOutcome two = run_cli("run '" + planar.string() + "' --sim-time --duration 0.4s --hand none --quiet");
  REQUIRE(one.exit_code == 0);
  REQUIRE(two.exit_code == 0);
  const std::string first = ":2: first (t = 0.100 s)\n";
  const std::string second = ":3: second\\nline (t = 0.250 s)\n";
  CHECK(one.err == flat.string() + first + flat.string() + second);
  CHECK(two.err == planar_script.string() + first + planar_script.string() + second);
  // Nothing of the log reaches the summary.
  CHECK(two.out.find("first") == std::string::npos);
}
