// The closed-loop expectations of 2-D test specs (`passes_validate`, `scenarios`): one
// validation of all seven 2-D scenarios (planar_validate.hpp) with the spec's options and
// the environment's "validate" thresholds, judged as the 1-D specs judge theirs
// (test_spec.cpp).
#include <algorithm>

#include "engine/harness/planar_test_spec.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/harness/spec_judging.hpp"

namespace hapscene {

std::vector<SpecOutcome> closed_loop_outcomes_2d(const PlanarScene& scene, const ValidateThresholds& thresholds,
                                                 const PlanarClosedLoopExpectations& expectations,
                                                 std::vector<std::pair<std::string, std::string>>* faults) {
  HarnessOptions options = expectations.options;
  options.thresholds = thresholds;
  if (expectations.start_m) options.free_start_planar_m = expectations.start_m;
  const PlanarValidationReport report = validate_planar_scene(scene, {}, options);
  for (const PlanarScenarioResult& s : report.scenarios) {
    for (const auto& f : s.metrics.script_faults) faults->emplace_back(f.message, f.text() + " in the " + s.scenario.name + " run");
  }

  std::vector<SpecOutcome> outcomes;
  const auto add = [&](std::string what, bool pass, std::string message) {
    outcomes.push_back({std::move(what), pass, std::move(message)});
  };
  if (expectations.passes_validate) {
    const std::string failed = failed_checks_text(report.scene_checks, report.scenarios);
    add("/passes_validate", report.pass == *expectations.passes_validate,
        std::string(*expectations.passes_validate ? "passes validate: " : "fails validate: ") +
            (failed.empty() ? "every check passed" : "failed " + failed));
  }

  // Expected behaviour per scenario (the names were checked when the spec was read).
  for (const PlanarScenarioExpectation& e : expectations.scenarios) {
    const auto found = std::find_if(report.scenarios.begin(), report.scenarios.end(),
                                    [&](const PlanarScenarioResult& r) { return r.scenario.name == e.scenario; });
    if (found == report.scenarios.end() || !found->scenario.applicable) {
      add(e.pointer, false, e.scenario + ": not applicable to this environment");
      continue;
    }
    const ScenarioSeen seen{found->metrics.oscillation, found->metrics.max_output_N, found->pass, found->checks};
    judge_scenario_expectation(e, e.scenario, seen, add);
  }
  return outcomes;
}

}  // namespace hapscene
