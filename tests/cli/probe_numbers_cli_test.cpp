// What `hapscene probe` prints for positions and what it takes as a range: each position
// is the double nearest the decimal value asked for, so the CSV reads 0.018, not
// 0.018000000000000002; a range whose parts mix a unit and bare numbers is refused. And
// plot's default figure name: the environment file's, not the "name" inside it.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using hapscene::test::run_cli;

TEST_CASE("probe: positions are the decimals asked for, and print as such") {
  const auto outcome = run_cli("probe environments/spring.json --x 0:30mm:3mm");
  REQUIRE(outcome.exit_code == 0);
  std::istringstream rows(outcome.out);
  std::string row;
  std::getline(rows, row);
  CHECK(row == "x_m,v_m_per_s,force_N,output_N");
  int i = 0;
  while (std::getline(rows, row)) {
    const std::string x = row.substr(0, row.find(','));
    CAPTURE(row);
    CHECK(std::stod(x) == std::stod(std::to_string(3 * i) + "e-3"));  // the nearest double
    CHECK(x.size() <= 5);                                             // "0.018", no noise
    ++i;
  }
  CHECK(i == 11);
  // Negative and fractional steps too.
  const auto down = run_cli("probe environments/spring.json --x 1.5mm:-1.5mm:-0.3mm");
  REQUIRE(down.exit_code == 0);
  CHECK(down.out.find("\n9e-04,") != std::string::npos);  // std::to_chars: the shortest form
  CHECK(down.out.find("\n-0.0012,") != std::string::npos);
  CHECK(down.out.find("00000") == std::string::npos);
}

TEST_CASE("probe: a range mixing bare numbers and a unit is refused, exit 2") {
  const auto mixed = run_cli("probe environments/spring.json --x 0:10:1mm");
  CHECK(mixed.exit_code == 2);
  CHECK(mixed.err.find("--x: \"10\" has no unit while another part of \"0:10:1mm\" has one") != std::string::npos);
  CHECK(mixed.out.empty());
  // A bare 0 is 0 in every unit; all bare is metres.
  CHECK(run_cli("probe environments/spring.json --x 0:10mm:1mm").exit_code == 0);
  CHECK(run_cli("probe environments/spring.json --x 0:0.01:0.001").exit_code == 0);
}

TEST_CASE("plot: without --output the figure is named after the environment's file, in the working folder") {
  const hapscene::test::ScratchFolder folder("plot_default_name");
  folder.write("my wall.json", R"({"name": "../escaped name", "effects": [{"type": "wall", "position": "10 mm", "stiffness": "300 N/m", "solid": "above"}]})");
  const auto outcome = hapscene::test::run_cli_in(folder.dir.string(), "plot 'my wall.json'");
  CHECK(outcome.exit_code == 0);
  CHECK(outcome.out == "wrote my wall.svg\n");
  CHECK(std::filesystem::exists(folder.dir / "my wall.svg"));
  CHECK_FALSE(std::filesystem::exists(folder.dir.parent_path() / "escaped name.svg"));
}

TEST_CASE("probe: a row where a script faulted has empty force fields, never a silent 0 N") {
  // The script faults beyond 5 mm; the spring beside it still pulls everywhere.
  const hapscene::test::ScratchFolder folder("probe_fault_rows");
  folder.write("edge.lua", "function force(s)\n  if s.x > 0.005 then error('past the edge') end\n  return 0\nend\n");
  folder.write("edge.json", R"({"effects": [{"type": "spring", "stiffness": "100 N/m"}, {"type": "script", "file": "edge.lua"}]})");
  const auto outcome = hapscene::test::run_cli_in(folder.dir.string(), "probe edge.json --x 0:10mm:2.5mm");
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.out ==
        "x_m,v_m_per_s,force_N,output_N\n"
        "0,0,0,0\n"
        "0.0025,0,-0.25,-0.25\n"
        "0.005,0,-0.5,-0.5\n"
        "0.0075,0,,\n"
        "0.01,0,,\n");
  CHECK(outcome.err.find("edge.lua:2: past the edge") != std::string::npos);
  // 2-D: the same, for both axes' columns.
  folder.write("edge2.lua", "function force(s)\n  if s.x > 0.005 then error('past the edge') end\n  return 0, 0\nend\n");
  folder.write("edge2.json", R"({"device": "haplink", "effects": [{"type": "script", "file": "edge2.lua"}]})");
  const auto planar = hapscene::test::run_cli_in(folder.dir.string(), "probe edge2.json --x 0:10mm:10mm --y 100mm:100mm:1mm");
  CHECK(planar.exit_code == 1);
  CHECK(planar.out ==
        "x_m,y_m,vx_m_per_s,vy_m_per_s,force_x_N,force_y_N,output_x_N,output_y_N\n"
        "0,0.1,0,0,0,0,0,0\n"
        "0.01,0.1,0,0,,,,\n");
}

TEST_CASE("probe: a range of plain numbers beyond the workspace is noted, with the range in mm") {
  // 0 to 30 m in steps of 1 m: almost surely meant in mm. Probed as asked, with a note.
  const auto metres = run_cli("probe environments/spring.json --x 0:30:1");
  CHECK(metres.exit_code == 0);
  CHECK(metres.err == "note: --x 0:30:1 is in metres (0 to 30 m), beyond the workspace [-0.05, 0.045] m; did you "
                      "mean 0mm:30mm:1mm?\n");
  CHECK(metres.out.find("\n30,0,") != std::string::npos);
  // Units given, or plain numbers inside the workspace: nothing to note.
  CHECK(run_cli("probe environments/spring.json --x 0:30mm:1mm").err.empty());
  CHECK(run_cli("probe environments/spring.json --x 0:0.03:0.001").err.empty());
  // 2-D: each axis against the box round the workspace.
  const auto planar = run_cli("probe environments/planar/haplink_box_inside.json --x -10:10:10 --y 120:130:10");
  CHECK(planar.exit_code == 0);
  CHECK(planar.err.find("note: --x -10:10:10 is in metres (-10 to 10 m), beyond the workspace") != std::string::npos);
  CHECK(planar.err.find("did you mean 120mm:130mm:10mm?") != std::string::npos);
}
