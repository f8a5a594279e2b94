// `hapscene plot` and `run --plot` on 2-DOF environments as users call them: the figure
// written (well-formed enough to hold its parts, byte-identical run to run), the exit
// codes, and the options of the other dimension refused with exit 2.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

namespace {

const std::string kBox = "environments/planar/haplink_box_inside.json";

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

void check_figure(const std::string& svg) {
  CHECK(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg ", 0) == 0);
  CHECK(svg.size() > 1000);
  CHECK(svg.substr(svg.size() - 7) == "</svg>\n");
  CHECK(svg.find("nan") == std::string::npos);
  CHECK(svg.find("inf") == std::string::npos);
  CHECK(count(svg, "<g id=\"quiver\"") == 1);
  CHECK(count(svg, "<rect class=\"shape\"") == 1);
  CHECK(count(svg, "<polyline id=\"handle-path\"") == 1);
  CHECK(count(svg, "<polyline id=\"proxy-path\"") == 1);
  CHECK(count(svg, "<svg") == 1);
}

}  // namespace

TEST_CASE("planar plot: writes the figure, exit 0, the same bytes every time" * doctest::test_suite("threaded")) {
  const ScratchFolder folder("planar_plot_cli");
  const std::string a = (folder.dir / "a.svg").string();
  const std::string b = (folder.dir / "b.svg").string();
  const CliOutcome first = run_cli("plot " + kBox + " --output '" + a + "'");
  REQUIRE(first.exit_code == 0);
  CHECK(first.out == "wrote " + a + "\n");
  CHECK(first.err == "");
  REQUIRE(run_cli("plot " + kBox + " --output '" + b + "'").exit_code == 0);
  const std::string svg = slurp_file(a);
  check_figure(svg);
  CHECK(svg == slurp_file(b));
  // haplink's workspace 110 mm x 75 mm: 24 x 16 grid points by default; --grid 10: 10 x 7.
  CHECK(svg.find("sweep (a raster of 7 rows") != std::string::npos);
  REQUIRE(run_cli("plot " + kBox + " --grid 10 --width 700 --scenario press --output '" + b + "'").exit_code == 0);
  const std::string small = slurp_file(b);
  check_figure(small);
  CHECK(small.find("width=\"700\"") != std::string::npos);
  CHECK(small.find("press (into the box") != std::string::npos);
  const std::size_t begin = small.find("<g id=\"quiver\"");
  const std::string quiver = small.substr(begin, small.find("</g>", begin) - begin);
  CHECK(count(quiver, "<path ") + count(quiver, "<circle ") == 70);
}

TEST_CASE("planar plot: every 2-DOF scenario and shipped scene draws" * doctest::test_suite("threaded")) {
  const ScratchFolder folder("planar_plot_scenarios");
  const std::string svg = (folder.dir / "f.svg").string();
  for (const char* scenario : {"line", "circle"}) {
    CAPTURE(scenario);
    CHECK(run_cli("plot environments/planar/haply2diy_v3_circle_outside.json --scenario " + std::string(scenario) +
                  " --output '" + svg + "'")
              .exit_code == 0);
    CHECK(slurp_file(svg).find("<circle class=\"shape\"") != std::string::npos);
  }
}

TEST_CASE("planar plot: press without a shape draws the field only and says so, exit 0") {
  const ScratchFolder folder("planar_plot_no_shape");
  const std::string env = folder.write("damper.json", R"({"name": "d", "device": "haplink", "effects": [{"type": "damper", "damping": 1}]})").string();
  const std::string svg = (folder.dir / "d.svg").string();
  const CliOutcome outcome = run_cli("plot '" + env + "' --scenario press --output '" + svg + "'");
  CHECK(outcome.exit_code == 0);
  CHECK(outcome.err == "note: press: no shape to press into; the figure shows the force field only\n");
  const std::string figure = slurp_file(svg);
  CHECK(figure.find("<g id=\"quiver\"") != std::string::npos);
  CHECK(figure.find("handle-path") == std::string::npos);
}

TEST_CASE("planar plot: 1-DOF options on a 2-DOF scene and 2-DOF options on a 1-DOF one exit 2") {
  const auto refused = [](const std::string& args, const std::string& message) {
    const CliOutcome outcome = run_cli(args + " --output /dev/null");
    CAPTURE(args);
    CHECK(outcome.exit_code == 2);
    CHECK(outcome.err.find(message) != std::string::npos);
    CHECK(outcome.out == "");
  };
  refused("plot " + kBox + " --noise 1", "--noise: only for a 1-DOF environment");
  refused("plot " + kBox + " --start 1mm", "--start: only for a 1-DOF environment");
  refused("plot " + kBox + " --scenario hold", "\"hold\" is a 1-DOF scenario; a 2-DOF environment takes sweep, press");
  refused("plot " + kBox + " --scenario circel", "did you mean \"circle\"?");
  refused("plot " + kBox + " --scenario sweep,press", "plot draws one scenario");
  refused("plot " + kBox + " --grid 1", "--grid: must be in [2, 200]");
  refused("plot " + kBox + " --width 10", "--width");
  refused("plot environments/wall.json --grid 10", "--grid: only for a 2-DOF environment");
  refused("plot environments/wall.json --width 800", "--width: only for a 2-DOF environment");
  refused("plot environments/wall.json --scenario circle", "unknown scenario \"circle\"");
  const CliOutcome onto_input = run_cli("plot " + kBox + " --output " + kBox);
  CHECK(onto_input.exit_code == 2);
  CHECK(onto_input.err.find("is an input file") != std::string::npos);
}

TEST_CASE("planar run --plot: the run's figure, and its output checked before the run" * doctest::test_suite("threaded")) {
  const ScratchFolder folder("planar_run_plot");
  const std::string svg = (folder.dir / "run.svg").string();
  const std::string log = (folder.dir / "run.csv").string();
  const CliOutcome run = run_cli("run " + kBox + " --sim-time --duration 3s --hand line --plot '" + svg + "' --log '" +
                                 log + "'");
  REQUIRE(run.exit_code == 0);
  CHECK(run.out.find("  plot             " + svg + "\n") != std::string::npos);
  const std::string figure = slurp_file(svg);
  check_figure(figure);
  CHECK(figure.find("run, hand line") != std::string::npos);
  // The same run gives the same figure.
  const std::string again = (folder.dir / "again.svg").string();
  REQUIRE(run_cli("run " + kBox + " --sim-time --duration 3s --hand line --plot '" + again + "'").exit_code == 0);
  CHECK(slurp_file(again) == figure);

  const CliOutcome same = run_cli("run " + kBox + " --sim-time --duration 0.1s --log '" + log + "' --plot '" + log + "'");
  CHECK(same.exit_code == 2);
  CHECK(same.err.find("is also given to --log") != std::string::npos);
  CHECK(run_cli("run " + kBox + " --sim-time --duration 0.1s --plot " + kBox).exit_code == 2);
  CHECK(run_cli("run " + kBox + " --sim-time --duration 0.1s --plot '" + (folder.dir / "no" / "x.svg").string() + "'")
            .exit_code == 2);
  // A figure that cannot be written is a failure of the command (exit 1), after the run.
  const CliOutcome full = run_cli("run " + kBox + " --sim-time --duration 0.1s --plot /dev/full");
  CHECK(full.exit_code == 1);
  CHECK(full.err == "hapscene: /dev/full: write failed: No space left on device\n");
}
