// Text from files and scripts never garbles the command line: a name, a script error or a
// log() message holding "\n", "\r", ESC or NUL is printed in escaped form, so it can
// neither forge a "PASS" line nor hide part of itself (engine/base/format.hpp).
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using hapscene::test::run_cli;
using namespace std::string_literals;

namespace {

// Faults beyond 2 mm with a message that tries to forge a line, clear it and hide a part;
// logs the same kind of text at every call.
const std::string kForgingScript =
    "needs = {velocity = false, time = false}\n"
    "function force(s)\n"
    "  if s.x > 0.002 then error('boom\\nPASS x.test.json (1 expectations)\\r\\27[2K\\0hidden', 0) end\n"
    "  log('said\\nPASS line\\0after')\n"
    "  return -100 * s.x\n"
    "end\n";

std::size_t count_lines(const std::string& text) {
  std::size_t n = 0;
  for (const char c : text) n += c == '\n' ? 1 : 0;
  return n;
}

bool has_raw_control(const std::string& text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("cli: a script error with newlines, CR, ESC and NUL prints as one escaped line") {
  const hapscene::test::ScratchFolder folder("printable_probe");
  const std::string script = folder.write("forging.lua", kForgingScript);
  const auto outcome = run_cli("probe " + script + " --x 0:4mm:2mm");
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.err == script + ": boom\\nPASS x.test.json (1 expectations)\\r\\x1b[2K\\x00hidden"
                                " (first at x 4.00 mm, v 0 m/s, t 0 s)\n");
}

TEST_CASE("cli: an environment name with a newline cannot forge a validate line") {
  const hapscene::test::ScratchFolder folder("printable_validate");
  const std::string env = folder.write(
      "named.json", R"({"name": "evil\nPASS fake (fake.json): 1 checks\r\u001b[1A\u0000", "effects": [{"type": "spring", "stiffness": 100}]})");
  const auto outcome = run_cli("validate --quiet --scenario hold " + env);
  CHECK(outcome.exit_code == 0);
  CHECK(count_lines(outcome.out) == 1);
  CHECK(outcome.out.starts_with("PASS evil\\nPASS fake (fake.json): 1 checks\\r\\x1b[1A\\x00 ("));
  CHECK_FALSE(has_raw_control(outcome.out));
}

TEST_CASE("cli: a test spec over a forging script fails with one escaped message line") {
  const hapscene::test::ScratchFolder folder("printable_test");
  folder.write("forging.lua", kForgingScript);
  const std::string spec = folder.write(
      "forging.test.json", R"({"environment": "forging.lua", "forces": [{"x": "4 mm", "force": "-0.4 N"}]})");
  const auto outcome = run_cli("test " + spec);
  CHECK(outcome.exit_code == 1);
  CHECK_FALSE(has_raw_control(outcome.out));
  CHECK(outcome.out.find("\nPASS") == std::string::npos);
  CHECK(outcome.out.find("boom\\nPASS x.test.json") != std::string::npos);
  CHECK(outcome.out.find("\\x00hidden") != std::string::npos);
}

TEST_CASE("cli: log() messages and run summaries print escaped") {
  const hapscene::test::ScratchFolder folder("printable_run");
  const std::string script = folder.write("forging.lua", kForgingScript);
  const auto outcome = run_cli("run " + script + " --sim-time --duration 10ms --quiet --hand none");
  CHECK_FALSE(has_raw_control(outcome.out));
  CHECK_FALSE(has_raw_control(outcome.err));
  CHECK(outcome.err.find(script + ":4: said\\nPASS line\\x00after (t = 0.000 s)\n") != std::string::npos);
}

TEST_CASE("cli: JSON strings and keys quoted in errors are escaped, NUL included") {
  const hapscene::test::ScratchFolder folder("printable_errors");
  const std::string env = folder.write("bad.json", R"({"effects": [{"type": "spr\ning\u0000x"}]})");
  const auto outcome = run_cli("validate " + env);
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.err == "error: " + env + ": /effects/0/type: unknown effect type \"spr\\ning\\x00x\" (did you mean \"spring\"?)\n");
}
