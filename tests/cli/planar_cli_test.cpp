// The command line on 2-DOF environments: probe's grid and run's log, with their exact
// headers (public interfaces), and the options' 2-D forms and errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene::test;

TEST_CASE("planar probe: one row per grid point with the exact header, the box pushes out through its nearest side") {
  const CliOutcome probe = run_cli(
      "probe environments/planar/haplink_box_inside.json --x -30mm:-10mm:10mm --y 125mm:125mm:1mm --v 0.1,0");
  REQUIRE(probe.exit_code == 0);
  CHECK(probe.out ==
        "x_m,y_m,vx_m_per_s,vy_m_per_s,force_x_N,force_y_N,output_x_N,output_y_N\n"
        "-0.03,0.125,0.1,0,-2.0000000000000004,0,-2,0\n"  // nearest: the left side (a tie with the top)
        "-0.02,0.125,0.1,0,0,2.0000000000000018,0,2\n"    // the top, 10 mm away
        "-0.01,0.125,0.1,0,2,0,2,0\n");                   // the right side (a tie with the top)
}

TEST_CASE("planar probe: 2-D options are refused on 1-D environments and required on 2-D ones") {
  CHECK(run_cli("probe environments/spring.json --x 0:1mm:1mm --y 0:1mm:1mm").exit_code == 2);
  const CliOutcome no_y = run_cli("probe environments/planar/haplink_box_inside.json --x 0:1mm:1mm");
  CHECK(no_y.exit_code == 2);
  CHECK(no_y.err.find("--y START:STOP:STEP is required") != std::string::npos);
  const CliOutcome bad_v = run_cli("probe environments/planar/haplink_box_inside.json --x 0:1mm:1mm --y 0:1mm:1mm --v 3");
  CHECK(bad_v.exit_code == 2);
  CHECK(bad_v.err.find("takes VX,VY") != std::string::npos);
  const CliOutcome grid = run_cli("probe environments/planar/haplink_box_inside.json --x 0:1:1um --y 0:1:1um");
  CHECK(grid.exit_code == 2);
}

TEST_CASE("planar run: --log writes the exact 2-D header and one row per tick") {
  ScratchFolder scratch("planar_run");
  const std::string log = (scratch.dir / "run.csv").string();
  const CliOutcome outcome = run_cli("run environments/planar/haply2diy_v3_box_outside.json --sim-time --duration 0.5s "
                                     "--hand circle --log '" + log + "'");
  REQUIRE(outcome.exit_code == 0);
  CHECK(outcome.out.find("on sim:haply2diy_v3") != std::string::npos);
  std::istringstream lines(slurp_file(log));
  std::string line;
  std::getline(lines, line);
  CHECK(line ==
        "t_s,x_m,y_m,vx_m_per_s,vy_m_per_s,force_x_N,force_y_N,output_x_N,output_y_N,duty_1,direction_1,duty_2,"
        "direction_2");
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    CHECK(std::count(line.begin(), line.end(), ',') == 12);
  }
  CHECK(rows == 500);
}

TEST_CASE("planar run: options of the other dimension and mixed 1-D and 2-D environments are refused") {
  CHECK(run_cli("run environments/planar/haplink_box_inside.json --sim-time --hold 10mm").exit_code == 2);
  CHECK(run_cli("run environments/planar/haplink_box_inside.json --sim-time --start 1,2").exit_code == 2);
  CHECK(run_cli("run environments/planar/haplink_box_inside.json environments/spring.json --sim-time").exit_code == 2);
  CHECK(run_cli("run environments/spring.json --sim-time --hold 1mm,2mm").exit_code == 2);
  // A hold point the linkage cannot reach (the Haplink's arm is 170 mm long).
  const CliOutcome far = run_cli("run environments/planar/haplink_box_inside.json --sim-time --hand hold --hold 0,300mm");
  CHECK(far.exit_code == 2);
  CHECK(far.err.find("--hold: the haplink cannot put its handle at (0, 0.3) m") != std::string::npos);
}

// validate and plot take 2-DOF scenes: planar_validate_cli_test.cpp, planar_plot_cli_test.cpp.

TEST_CASE("planar run: a --log that would overwrite the environment is refused before anything runs") {
  ScratchFolder scratch("planar_log_overwrite");
  const auto environment = scratch.write("cage.json", slurp_file(HAPSCENE_SOURCE_DIR "/environments/planar/haplink_box_outside.json"));
  const std::string before = slurp_file(environment);
  const CliOutcome outcome =
      run_cli("run '" + environment.string() + "' --sim-time --duration 0.1s --log '" + environment.string() + "'");
  CHECK(outcome.exit_code == 2);
  CHECK(slurp_file(environment) == before);
}
