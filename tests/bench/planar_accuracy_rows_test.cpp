// `hapscene bench --accuracy` prints 2-D rows after the 1-D ones (`--axes 2`: those
// alone): the simulated 2-DOF plant's integration error for each kinematics family's
// shipped profile, every scenario, integrator and substep count at the chosen rate, each
// finite.
#include <doctest/doctest.h>

#include <set>
#include <sstream>
#include <string>

#include "tests/cli/cli_support.hpp"

using namespace hapscene::test;

TEST_CASE("bench --accuracy: 2-D rows for both kinematics families, every case, finite" *
          doctest::test_suite("sweeps")) {
  // The 2-D rows alone (--axes 2); the 1-D ones come first without it.
  const CliOutcome bench = run_cli("bench --accuracy --axes 2 --rate 1000");
  REQUIRE(bench.exit_code == 0);
  const std::string header =
      "device        scenario rate_Hz integ  sub   ms_per_s integ_rms_um integ_max_um travel_mm\n";
  const std::size_t table = bench.out.find(header);
  REQUIRE(table != std::string::npos);
  CHECK(bench.out.starts_with("integration error of the simulated 2-DOF plant"));
  CHECK(bench.out.find("pos_rms_um") == std::string::npos);  // no 1-D rows
  std::istringstream rows(bench.out.substr(table + header.size()));
  std::string row;
  std::set<std::string> seen;
  int count = 0;
  while (std::getline(rows, row) && !row.empty() && !row.starts_with("wrote")) {
    std::istringstream cells(row);
    std::string device, scenario, rate, integrator, substeps;
    double ms_per_s = -1, rms_um = -1, max_um = -1, travel_mm = -1;
    cells >> device >> scenario >> rate >> integrator >> substeps >> ms_per_s >> rms_um >> max_um >> travel_mm;
    CAPTURE(row);
    REQUIRE_FALSE(cells.fail());
    CHECK(rate == "1000");
    CHECK(ms_per_s > 0.0);
    CHECK(rms_um >= 0.0);
    CHECK(max_um >= rms_um);
    CHECK(travel_mm > 10.0);
    // RK4 at the default 4 substeps is accurate to well under a micrometre.
    if (integrator == "rk4" && substeps == "4") CHECK(max_um < 1.0);
    seen.insert(device + " " + scenario + " " + integrator + " " + substeps);
    ++count;
  }
  // 2 devices x 3 scenarios x 2 integrators x 4 substep counts.
  CHECK(count == 48);
  CHECK(seen.size() == 48);
  CHECK(seen.count("haplink release euler 1") == 1);
  CHECK(seen.count("haply2diy_v3 wall rk4 8") == 1);
}

TEST_CASE("bench --accuracy: --axes and a rate the 2-D sweep does not run are refused, exit 2") {
  CHECK(run_cli("bench --accuracy --axes 3").exit_code == 2);
  const CliOutcome rate = run_cli("bench --accuracy --axes 2 --rate 250");
  CHECK(rate.exit_code == 2);
  CHECK(rate.err.find("--rate: the 2-D rows run at 500, 1000, 2000 or 5000 Hz") != std::string::npos);
  CHECK(run_cli("bench --accuracy --axes 2 --svg x.svg").exit_code == 2);
}
