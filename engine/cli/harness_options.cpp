#include "engine/cli/harness_options.hpp"

#include <string>

namespace hapscene {

std::uint64_t parse_seed(const Arguments& arguments, const std::string& text) {
  try {
    std::size_t used = 0;
    const std::uint64_t seed = std::stoull(text, &used);
    if (used == text.size() && !text.starts_with('-')) return seed;
  } catch (const std::exception&) {
  }
  arguments.fail("--seed: expected a whole number, got \"" + text + "\"");
}

HarnessOptions take_harness_options(Arguments& arguments) {
  HarnessOptions o;
  o.hand_stiffness_N_per_m = arguments.take_quantity("hand-stiffness", Quantity::stiffness_N_per_m)
                                 .value_or(o.hand_stiffness_N_per_m);
  o.hand_damping_N_s_per_m = arguments.take_quantity("hand-damping", Quantity::damping_N_s_per_m)
                                 .value_or(o.hand_damping_N_s_per_m);
  o.hand_mass_kg = arguments.take_quantity("hand-mass", Quantity::mass_kg).value_or(o.hand_mass_kg);
  if (!(o.hand_stiffness_N_per_m > 0.0)) arguments.fail("--hand-stiffness: must be > 0");
  if (o.hand_damping_N_s_per_m < 0.0) arguments.fail("--hand-damping: must be >= 0");
  if (o.hand_mass_kg < 0.0) arguments.fail("--hand-mass: must be >= 0");
  o.noise_counts = arguments.take_quantity("noise", Quantity::dimensionless).value_or(-1.0);
  if (const auto seed = arguments.take_value("seed")) o.seed = parse_seed(arguments, *seed);
  o.free_start_m = arguments.take_quantity("start", Quantity::length_m).value_or(o.free_start_m);
  return o;
}

std::vector<ScenarioKind> take_scenarios(Arguments& arguments) {
  std::vector<ScenarioKind> kinds;
  const std::optional<std::string> list = arguments.take_value("scenario");
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
    kinds.push_back(*kind);
    begin = end + 1;
  }
  return kinds;
}

}  // namespace hapscene
