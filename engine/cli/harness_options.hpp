#pragma once
// Command-line options shared by `validate`, `plot` and `test`: the virtual hand, the
// sensor noise, the seed, the free start and the scenario selection.
#include <optional>
#include <string>
#include <vector>

#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/harness/validate_kind.hpp"

namespace hapscene {

// Takes --hand-stiffness, --hand-damping, --hand-mass, --noise, --seed, --start.
HarnessOptions take_harness_options(Arguments& arguments);

// "X,Y" as two lengths, each in `option`'s range (a 2-DOF environment's --start, --hold).
Vec2 parse_planar_point(const Arguments& arguments, const std::string& name, const std::string& text,
                        const QuantityOption& option);

// --start of validate's free scenario: X for one axis (into a double), X,Y for two (a
// Vec2), each in the option's range; fails `arguments` (exit 2) otherwise.
void parse_free_start(const Arguments& arguments, const std::string& text, double* x_m);
void parse_free_start(const Arguments& arguments, const std::string& text, Vec2* x_m);

// --scenario NAME[,NAME...] (taken already: `list` empty when not given) for a scene of N
// axes: the scenarios in order, empty when not given (all of them). Fails `arguments`
// (exit 2) on an unknown or repeated name (scenario_list_problem).
template <int N>
std::vector<ValidateScenarioOf<N>> parse_scenarios(const Arguments& arguments, const std::optional<std::string>& list) {
  if (!list) return {};
  const std::vector<std::string> names = split_names(*list);
  const std::string problem = scenario_list_problem<N>(names);
  if (!problem.empty()) arguments.fail("--scenario: " + problem);
  return scenario_list<N>(names);
}

}  // namespace hapscene
