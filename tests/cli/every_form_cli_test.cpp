// Every command that takes an environment takes every form the docs name: a 1-D JSON
// file, a 2-D JSON file (a planar device) and a script (.lua, a one-effect environment),
// and answers with its own output, never an exception's text.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using hapscene::test::run_cli;

namespace {

constexpr const char* kForms[] = {"environments/wall.json", "environments/planar/haplink_box_inside.json",
                                  "scripts/bumps.lua"};

bool planar(const std::string& form) { return form.find("planar") != std::string::npos; }

}  // namespace

TEST_CASE("cli: run, probe, validate, plot and bench take each form of environment" *
          doctest::test_suite("sweeps")) {
  const hapscene::test::ScratchFolder folder("every_form");
  for (const std::string form : kForms) {
    const std::string probe_range = planar(form) ? "--x -10mm:10mm:10mm --y 120mm:130mm:10mm" : "--x -10mm:10mm:5mm";
    const std::string svg = (folder.dir / "figure.svg").string();
    const std::string commands[] = {
        "run " + form + " --sim-time -d 0.2s --quiet",
        "probe " + form + " " + probe_range,
        "validate " + form + " --scenario sweep --quiet",
        "plot " + form + " --output " + svg,
        "bench " + form + " --seconds 0.2 --passes 1",
    };
    for (const std::string& command : commands) {
      CAPTURE(command);
      const auto outcome = run_cli(command);
      CHECK(outcome.exit_code == 0);
      CHECK_FALSE(outcome.out.empty());
      CHECK(outcome.err.find("exception") == std::string::npos);
      CHECK(outcome.err.find("terminate") == std::string::npos);
    }
  }
}
