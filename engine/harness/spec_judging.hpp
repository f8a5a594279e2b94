#pragma once
// What test specs of every kind (test_spec_kind.hpp) judge alike once validate has run:
// `passes_validate` against the checks that failed, and a scenario expectation
// (half-cycles, frequency, force, pass, checks that must fail) against one scenario's
// result. Internal to the harness.
#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/base/format.hpp"
#include "engine/harness/checks.hpp"
#include "engine/harness/metrics.hpp"

namespace hapscene {

// A scenario expectation, as written (docs/reference/test-specs.md): the scenario's name
// (one of its kind's, checked when the spec is read) and what its run must show.
struct ScenarioExpectation {
  std::string pointer;  // "/scenarios/0"
  std::string scenario;
  std::optional<int> min_half_cycles, max_half_cycles;
  std::optional<std::pair<double, double>> frequency_Hz;
  std::optional<double> max_force_N;
  std::optional<bool> pass;
  std::vector<std::string> fail;  // checks that must fail
};

// "scene/effects, press/passivity, ...": every failed check of a report, or empty.
// `Scenarios` holds results with `.scenario.name` and `.checks`.
template <typename Scenarios>
std::string failed_checks_text(const std::vector<CheckResult>& scene_checks, const Scenarios& scenarios) {
  std::string failed;
  for (const CheckResult& c : scene_checks) {
    if (!c.pass) failed += std::string(failed.empty() ? "" : ", ") + "scene/" + c.name;
  }
  for (const auto& s : scenarios) {
    for (const CheckResult& c : s.checks) {
      if (!c.pass) failed += (failed.empty() ? "" : ", ") + s.scenario.name + "/" + c.name;
    }
  }
  return failed;
}

// One scenario's result as the expectations read it.
struct ScenarioSeen {
  const std::optional<OscillationMetrics>& oscillation;
  double max_output_N;
  bool pass;
  const std::vector<CheckResult>& checks;
};

// Judges expectation `e` (pointer, min/max_half_cycles, frequency_Hz, max_force_N, pass,
// fail) of the scenario `name`; `add(what, pass, message)` takes each outcome.
template <typename Expectation, typename Add>
void judge_scenario_expectation(const Expectation& e, const std::string& name, const ScenarioSeen& s, Add add) {
  const int half_cycles = s.oscillation ? s.oscillation->half_cycles : 0;
  if (e.min_half_cycles) {
    add(e.pointer + "/min_half_cycles", half_cycles >= *e.min_half_cycles,
        printf_string("%s: at least %d half-cycles, got %d", name.c_str(), *e.min_half_cycles, half_cycles));
  }
  if (e.max_half_cycles) {
    add(e.pointer + "/max_half_cycles", half_cycles <= *e.max_half_cycles,
        printf_string("%s: at most %d half-cycles, got %d", name.c_str(), *e.max_half_cycles, half_cycles));
  }
  if (e.frequency_Hz) {
    const double f_Hz = s.oscillation ? s.oscillation->frequency_Hz : 0.0;
    add(e.pointer + "/frequency", f_Hz >= e.frequency_Hz->first && f_Hz <= e.frequency_Hz->second,
        printf_string("%s: frequency in [%g, %g] Hz, got %.3f Hz", name.c_str(), e.frequency_Hz->first,
                      e.frequency_Hz->second, f_Hz));
  }
  if (e.max_force_N) {
    add(e.pointer + "/max_force", s.max_output_N <= *e.max_force_N,
        printf_string("%s: force at most %g N, got %.4g N", name.c_str(), *e.max_force_N, s.max_output_N));
  }
  if (e.pass) {
    add(e.pointer + "/pass", s.pass == *e.pass,
        name + (*e.pass ? ": every check passes" : ": some check fails") + (s.pass ? " (all passed)" : " (some failed)"));
  }
  for (const std::string& check : e.fail) {
    const auto found =
        std::find_if(s.checks.begin(), s.checks.end(), [&](const CheckResult& c) { return c.name == check; });
    const bool failed = found != s.checks.end() && !found->pass;
    add(e.pointer + "/fail", failed,
        name + ": check " + check + " fails: " +
            (found == s.checks.end() ? "not run" : (failed ? "yes, " : "no, ") + found->detail));
  }
}

// Judges `passes_validate` and the scenario expectations against a validation `report` of
// either kind (its scene checks and scenario results, each with `.scenario.name`,
// `.scenario.applicable`, `.metrics`, `.pass` and `.checks`); `add(what, pass, message)`
// takes each outcome.
template <typename Report, typename Add>
void judge_closed_loop(const Report& report, const std::optional<bool>& passes_validate,
                       const std::vector<ScenarioExpectation>& scenarios, Add add) {
  if (passes_validate) {
    const std::string failed = failed_checks_text(report.scene_checks, report.scenarios);
    add("/passes_validate", report.pass == *passes_validate,
        std::string(*passes_validate ? "passes validate: " : "fails validate: ") +
            (failed.empty() ? "every check passed" : "failed " + failed));
  }
  for (const ScenarioExpectation& e : scenarios) {
    const auto found = std::find_if(report.scenarios.begin(), report.scenarios.end(),
                                    [&](const auto& r) { return r.scenario.name == e.scenario; });
    if (found == report.scenarios.end() || !found->scenario.applicable) {
      add(e.pointer, false, e.scenario + ": not applicable to this environment");
      continue;
    }
    const ScenarioSeen seen{found->metrics.oscillation, found->metrics.max_output_N, found->pass, found->checks};
    judge_scenario_expectation(e, e.scenario, seen, add);
  }
}

}  // namespace hapscene
