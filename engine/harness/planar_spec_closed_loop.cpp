// The closed-loop expectations of 2-D test specs (`passes_validate`, `scenarios`): one
// validation of all seven 2-D scenarios (planar_validate.hpp) with the spec's options and
// the environment's "validate" thresholds, judged as the 1-D specs judge theirs
// (test_spec.cpp).
#include <algorithm>

#include "engine/base/format.hpp"
#include "engine/harness/planar_test_spec.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

std::vector<SpecOutcome> closed_loop_outcomes_2d(const PlanarScene& scene, const std::string& environment_path,
                                                 const PlanarClosedLoopExpectations& expectations,
                                                 std::vector<std::pair<std::string, std::string>>* faults) {
  HarnessOptions options = expectations.options;
  options.thresholds = load_planar_environment(environment_path).validate;
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
    std::string failed;
    for (const CheckResult& c : report.scene_checks) {
      if (!c.pass) failed += std::string(failed.empty() ? "" : ", ") + "scene/" + c.name;
    }
    for (const PlanarScenarioResult& s : report.scenarios) {
      for (const CheckResult& c : s.checks) {
        if (!c.pass) failed += (failed.empty() ? "" : ", ") + s.scenario.name + "/" + c.name;
      }
    }
    add("/passes_validate", report.pass == *expectations.passes_validate,
        std::string(*expectations.passes_validate ? "passes validate: " : "fails validate: ") +
            (failed.empty() ? "every check passed" : "failed " + failed));
  }

  // Expected behaviour per scenario (the names were checked when the spec was read).
  for (const PlanarScenarioExpectation& e : expectations.scenarios) {
    const auto found = std::find_if(report.scenarios.begin(), report.scenarios.end(),
                                    [&](const PlanarScenarioResult& r) { return r.scenario.name == e.scenario; });
    const std::string& name = e.scenario;
    if (found == report.scenarios.end() || !found->scenario.applicable) {
      add(e.pointer, false, name + ": not applicable to this environment");
      continue;
    }
    const PlanarScenarioResult& s = *found;
    const std::optional<OscillationMetrics>& o = s.metrics.oscillation;
    const int half_cycles = o ? o->half_cycles : 0;
    if (e.min_half_cycles) {
      add(e.pointer + "/min_half_cycles", half_cycles >= *e.min_half_cycles,
          printf_string("%s: at least %d half-cycles, got %d", name.c_str(), *e.min_half_cycles, half_cycles));
    }
    if (e.max_half_cycles) {
      add(e.pointer + "/max_half_cycles", half_cycles <= *e.max_half_cycles,
          printf_string("%s: at most %d half-cycles, got %d", name.c_str(), *e.max_half_cycles, half_cycles));
    }
    if (e.frequency_Hz) {
      const double f_Hz = o ? o->frequency_Hz : 0.0;
      add(e.pointer + "/frequency", f_Hz >= e.frequency_Hz->first && f_Hz <= e.frequency_Hz->second,
          printf_string("%s: frequency in [%g, %g] Hz, got %.3f Hz", name.c_str(), e.frequency_Hz->first,
                        e.frequency_Hz->second, f_Hz));
    }
    if (e.max_force_N) {
      add(e.pointer + "/max_force", s.metrics.max_output_N <= *e.max_force_N,
          printf_string("%s: force at most %g N, got %.4g N", name.c_str(), *e.max_force_N, s.metrics.max_output_N));
    }
    if (e.pass) {
      add(e.pointer + "/pass", s.pass == *e.pass,
          name + (*e.pass ? ": every check passes" : ": some check fails") + (s.pass ? " (all passed)" : " (some failed)"));
    }
    for (const std::string& check : e.fail) {
      const auto c = std::find_if(s.checks.begin(), s.checks.end(), [&](const CheckResult& r) { return r.name == check; });
      const bool failed = c != s.checks.end() && !c->pass;
      add(e.pointer + "/fail", failed,
          name + ": check " + check + " fails: " + (c == s.checks.end() ? "not run" : (failed ? "yes, " : "no, ") + c->detail));
    }
  }
  return outcomes;
}

}  // namespace hapscene
