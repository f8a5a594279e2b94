// The maze closed loop on the simulated haplink: `hapscene run --hand line` drags the
// handle (the hand's spring against a force clamped to 2 N) right through the post
// standing on the shelf (x in (-30, -28) mm). The proxy stays on the post's right face, so
// all the while the handle is beyond the post the force pulls it back to the right; a
// renderer by penetration depth would push it out of the far side (to the left).
#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

namespace hapscene {

TEST_CASE("maze run: dragged through the post by the hand, the handle is pulled back to the side it came from") {
  const test::ScratchFolder folder("planar_maze_run");
  const std::string log = (folder.dir / "maze.csv").string();
  const test::CliOutcome run =
      test::run_cli("run environments/planar/haplink_maze.json --sim-time --hand line --log '" + log + "'");
  CAPTURE(run.err);
  CHECK(run.exit_code == 0);
  CHECK(run.out.find("script ok        scripts/planar/maze.lua") != std::string::npos);
  std::istringstream lines(test::slurp_file(log));
  std::string line;
  std::getline(lines, line);  // header: t_s,x_m,y_m,vx,vy,force_x_N,force_y_N,...
  int beyond = 0;
  double deepest_m = 0.0;
  while (std::getline(lines, line)) {
    double value[7];
    std::istringstream fields(line);
    std::string field;
    for (double& v : value) {
      std::getline(fields, field, ',');
      v = std::stod(field);
    }
    const double x_m = value[1], y_m = value[2], force_x_N = value[5];
    if (x_m < -0.030 && y_m > 0.121 && y_m < 0.145) {
      ++beyond;
      deepest_m = std::min(deepest_m, x_m);
      CHECK(force_x_N > 0.0);
    }
  }
  CHECK(beyond > 100);
  CHECK(deepest_m < -0.040);  // well past the post, not just into it
}

}  // namespace hapscene
