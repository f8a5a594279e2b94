// The closed-loop expectations of 2-D test specs (`passes_validate`, `scenarios`). The
// place where 2-D validate plugs in: run it on `scene` with `expectations.options` (and
// `start_m`), then judge each expectation as the 1-D specs do (test_spec.cpp). Until then
// each expectation FAILS with a message saying it cannot be judged yet.
#include "engine/harness/planar_test_spec.hpp"

namespace hapscene {

std::vector<SpecOutcome> closed_loop_outcomes_2d(const PlanarScene& scene, const std::string& environment_path,
                                                 const PlanarClosedLoopExpectations& expectations,
                                                 std::vector<std::pair<std::string, std::string>>* faults) {
  (void)scene;
  (void)environment_path;
  (void)faults;
  const std::string why = ": cannot be judged yet: closed-loop runs (validate) of 2-DOF scenes are not part of "
                          "test specs so far";
  std::vector<SpecOutcome> outcomes;
  if (expectations.passes_validate) {
    outcomes.push_back({"/passes_validate", false,
                        std::string(*expectations.passes_validate ? "passes validate" : "fails validate") + why});
  }
  for (const PlanarScenarioExpectation& e : expectations.scenarios) {
    outcomes.push_back({e.pointer, false, e.scenario + why});
  }
  return outcomes;
}

}  // namespace hapscene
