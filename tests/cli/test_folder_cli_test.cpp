// `hapscene test` where a user keeps their own specs: without arguments in a folder with
// no environments/ or scripts/, the specs under the current folder; a spec beside a script
// tests the script; an "environment" that names the wrong form of a file beside it is told
// the right one.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using hapscene::test::run_cli_in;

namespace {
constexpr const char* kBump = "function force(s)\n  return -100 * s.x\nend\n";
constexpr const char* kSpec = R"({"forces": [{"x": "10 mm", "force": "-1 N", "tolerance": "1e-9 N"}]})";
}  // namespace

TEST_CASE("test cli: without arguments in a folder of one's own specs, the specs under it") {
  const hapscene::test::ScratchFolder folder("test_own_folder");
  folder.write("lab/bump.lua", kBump);
  folder.write("lab/bump.test.json", kSpec);  // no "environment": bump.json is not there, bump.lua is
  const auto outcome = run_cli_in(folder.dir.string(), "test");
  CHECK(outcome.exit_code == 0);
  CHECK(outcome.out.find("PASS lab/bump.test.json (1 expectations)") != std::string::npos);
  // Nothing anywhere: said, exit 2.
  const hapscene::test::ScratchFolder empty("test_no_specs");
  const auto none = run_cli_in(empty.dir.string(), "test");
  CHECK(none.exit_code == 2);
  CHECK(none.err.find("no *.test.json under environments/, scripts/ or the current folder") != std::string::npos);
}

TEST_CASE("test cli: an environment named in the wrong form is told the file beside the spec") {
  const hapscene::test::ScratchFolder folder("test_wrong_form");
  folder.write("bump.lua", kBump);
  folder.write("bump.test.json", R"({"environment": "bump.json", "forces": [{"x": 0, "force": 0}]})");
  const auto outcome = run_cli_in(folder.dir.string(), "test bump.test.json");
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.err.find("bump.test.json: /environment: \"bump.json\" does not exist (did you mean \"bump.lua\", "
                         "beside it?)") != std::string::npos);
}
