#pragma once
// Command-line options shared by `validate`, `plot` and `test`: the virtual hand, the
// sensor noise, the seed, the free start and the scenario selection.
#include <optional>
#include <string>
#include <vector>

#include "engine/cli/arguments.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/harness/planar_validate_scenario.hpp"
#include "engine/harness/scenario.hpp"

namespace hapscene {

// Takes --hand-stiffness, --hand-damping, --hand-mass, --noise, --seed, --start.
HarnessOptions take_harness_options(Arguments& arguments);

// "X,Y" as two lengths, each in `option`'s range (a 2-DOF environment's --start, --hold).
Vec2 parse_planar_point(const Arguments& arguments, const std::string& name, const std::string& text,
                        const QuantityOption& option);

// --scenario NAME[,NAME...] for a 2-DOF environment (validate's planar scenarios); empty
// when not given (all of them).
std::vector<PlanarValidateKind> parse_planar_scenarios(const Arguments& arguments,
                                                       const std::optional<std::string>& list);

// Takes --scenario NAME[,NAME...]; empty when not given (all scenarios).
std::vector<ScenarioKind> take_scenarios(Arguments& arguments);
// The same for a list already taken (`list` empty: not given).
std::vector<ScenarioKind> parse_scenarios(const Arguments& arguments, const std::optional<std::string>& list);

}  // namespace hapscene
