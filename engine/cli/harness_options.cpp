#include "engine/cli/harness_options.hpp"

#include <algorithm>
#include <string>

#include "engine/base/units.hpp"
#include "engine/cli/option_definitions.hpp"

namespace hapscene {

HarnessOptions take_harness_options(Arguments& arguments) {
  HarnessOptions o;
  o.hand_stiffness_N_per_m = arguments.take(option::hand_stiffness).value_or(o.hand_stiffness_N_per_m);
  o.hand_damping_N_s_per_m = arguments.take(option::hand_damping).value_or(o.hand_damping_N_s_per_m);
  o.hand_mass_kg = arguments.take(option::hand_mass).value_or(o.hand_mass_kg);
  o.noise_counts = arguments.take(option::noise).value_or(-1.0);
  o.seed = arguments.take(option::seed).value_or(o.seed);
  o.free_start_m = arguments.take(option::free_start).value_or(o.free_start_m);
  return o;
}

std::vector<ScenarioKind> take_scenarios(Arguments& arguments) {
  return parse_scenarios(arguments, arguments.take_value("scenario"));
}

std::vector<ScenarioKind> parse_scenarios(const Arguments& arguments, const std::optional<std::string>& list) {
  std::vector<ScenarioKind> kinds;
  if (!list) return kinds;
  std::size_t begin = 0;
  while (begin <= list->size()) {
    const std::size_t end = std::min(list->find(',', begin), list->size());
    const std::string name = list->substr(begin, end - begin);
    const std::optional<ScenarioKind> kind = scenario_kind_named(name);
    if (!kind) {
      std::string message = "--scenario: unknown scenario \"" + name + "\" (one of sweep, press, release, hold, shake, free";
      const std::string suggestion = nearest_name(name, kScenarioNames);
      arguments.fail(message + (suggestion.empty() ? ")" : "; did you mean \"" + suggestion + "\"?)"));
    }
    // Each scenario once: a list is not a way to run one scenario a thousand times.
    if (std::find(kinds.begin(), kinds.end(), *kind) != kinds.end()) {
      arguments.fail("--scenario: \"" + name + "\" is listed twice");
    }
    kinds.push_back(*kind);
    begin = end + 1;
  }
  return kinds;
}

Vec2 parse_planar_point(const Arguments& arguments, const std::string& name, const std::string& text,
                        const QuantityOption& option) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
    arguments.fail("--" + name + ": a 2-DOF environment takes X,Y, got \"" + text + "\"");
  }
  const std::string what = arguments.command() + ": --" + name;
  return Vec2{{parse_option_quantity(text.substr(0, comma), option, what + " X"),
               parse_option_quantity(text.substr(comma + 1), option, what + " Y")}};
}

std::vector<PlanarValidateKind> parse_planar_scenarios(const Arguments& arguments,
                                                       const std::optional<std::string>& list) {
  std::vector<PlanarValidateKind> kinds;
  if (!list) return kinds;
  std::size_t begin = 0;
  while (begin <= list->size()) {
    const std::size_t end = std::min(list->find(',', begin), list->size());
    const std::string name = list->substr(begin, end - begin);
    const std::optional<PlanarValidateKind> kind = planar_validate_kind_named(name);
    if (!kind) {
      const std::string suggestion = nearest_name(name, kPlanarValidateNames);
      arguments.fail("--scenario: unknown scenario \"" + name +
                     "\" for a 2-DOF environment (one of sweep, press, swipe, release, hold, shake, free" +
                     (suggestion.empty() ? ")" : "; did you mean \"" + suggestion + "\"?)"));
    }
    if (std::find(kinds.begin(), kinds.end(), *kind) != kinds.end()) {
      arguments.fail("--scenario: \"" + name + "\" is listed twice");
    }
    kinds.push_back(*kind);
    begin = end + 1;
  }
  return kinds;
}

}  // namespace hapscene
