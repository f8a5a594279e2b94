// The environment's "validate" block reaches every command that runs the harness
// (validate, test, plot): the loader returns it beside the scene, not in it.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using hapscene::test::run_cli;
using hapscene::test::slurp_file;

namespace {

// The lab wall (500 N/m at +10 mm), with a validate block.
std::string wall_with(const std::string& validate_block) {
  return R"({"name": "strict", "validate": )" + validate_block +
         R"(, "effects": [{"type": "wall", "position": "10 mm", "stiffness": "500 N/m", "solid": "above"}]})";
}

}  // namespace

TEST_CASE("cli: validate, test and plot judge by the environment's validate block") {
  const hapscene::test::ScratchFolder folder("validate_block_cli");
  const std::string strict = folder.write("strict.json", wall_with(R"({"max_force": "0.5 N"})")).string();

  // validate: the block's max_force, not the safety limit, is the threshold.
  const auto validated = run_cli("validate " + strict + " --scenario sweep --quiet");
  CHECK(validated.exit_code == 1);
  CHECK(validated.out.find("sweep/max_force") != std::string::npos);

  // test: a spec of the same environment sees the same threshold.
  const std::string spec =
      folder.write("strict.test.json", R"({"scenarios": [{"scenario": "sweep", "fail": ["max_force"]}]})").string();
  const auto tested = run_cli("test " + spec);
  CHECK(tested.exit_code == 0);

  // plot: the block's stiff_threshold decides whether the wall is one to press.
  const std::string soft = folder.write("soft.json", wall_with(R"({"stiff_threshold": "1000 N/m"})")).string();
  const std::string svg = (folder.dir / "soft.svg").string();
  CHECK(run_cli("plot " + strict + " --scenario press --output " + svg).exit_code == 0);
  CHECK(slurp_file(svg).find("press (hand presses") != std::string::npos);
  CHECK(run_cli("plot " + soft + " --scenario press --output " + svg).exit_code == 0);
  CHECK(slurp_file(svg).find("press (hand") == std::string::npos);
}
