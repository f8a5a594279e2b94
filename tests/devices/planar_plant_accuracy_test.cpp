// The planar plant's integration error at a 1 kHz tick against a 10x-per-substep finer RK4
// run of the same loop (engine/bench/planar_accuracy.hpp), both families: the default
// integrator (RK4, 4 substeps) is accurate to well under a micrometre in every scenario
// (measured: tens of nanometres at most, with Coulomb friction's events; picometres without),
// and the error falls as the substeps grow (so the reference is the finer one).
#include <doctest/doctest.h>

#include "engine/bench/planar_accuracy.hpp"

using namespace hapscene;

TEST_CASE("planar plant accuracy: RK4 at 4 substeps per 1 kHz tick stays within 1 um of a fine run") {
  std::vector<PlanarAccuracyCase> cases;
  for (const PlanarAccuracyScenario scenario :
       {PlanarAccuracyScenario::release, PlanarAccuracyScenario::circle, PlanarAccuracyScenario::wall}) {
    cases.push_back({scenario, 1000.0, PlanarIntegrator::rk4, 4});
    cases.push_back({scenario, 1000.0, PlanarIntegrator::rk4, 8});
  }
  PlanarAccuracyOptions options;
  options.fine_step_s = 2e-5;  // 25x finer than the default's substep; enough for a test
  options.timed = false;
  for (const PlanarPlantExample& device : {example_haplink_plant(), example_haply2diy_v3_plant()}) {
    const std::vector<PlanarAccuracyResult> results = run_planar_accuracy(device, cases, options);
    REQUIRE(results.size() == cases.size());
    for (std::size_t i = 0; i < results.size(); i += 2) {
      const PlanarAccuracyResult& coarse = results[i];
      const PlanarAccuracyResult& finer = results[i + 1];
      CAPTURE(kPlanarAccuracyScenarioNames[static_cast<int>(coarse.which.scenario)]);
      CHECK(coarse.finite);
      CHECK(coarse.travel_m > 0.01);
      CHECK(coarse.integration_max_m < 1e-6);
      CHECK(coarse.integration_rms_m < 1e-7);
      CHECK(finer.integration_rms_m < coarse.integration_rms_m);
    }
  }
}

TEST_CASE("planar plant accuracy: semi-implicit Euler runs too, and is the less accurate choice") {
  const std::vector<PlanarAccuracyCase> cases{{PlanarAccuracyScenario::circle, 1000.0, PlanarIntegrator::semi_implicit_euler, 4},
                                              {PlanarAccuracyScenario::circle, 1000.0, PlanarIntegrator::rk4, 4}};
  PlanarAccuracyOptions options;
  options.fine_step_s = 2e-5;
  options.timed = false;
  const std::vector<PlanarAccuracyResult> results = run_planar_accuracy(example_haply2diy_v3_plant(), cases, options);
  CHECK(results[0].finite);
  CHECK(results[0].integration_max_m < 1e-4);  // measured 19 um
  CHECK(results[0].integration_rms_m > 100.0 * results[1].integration_rms_m);
}
