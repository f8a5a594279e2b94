#include "engine/harness/validate_kind.hpp"

#include <algorithm>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/units.hpp"

namespace hapscene {

template <int N>
std::string scenario_list_problem(const std::vector<std::string>& names) {
  using Kind = ValidateKindOf<N>;
  std::vector<std::string_view> seen;
  for (const std::string& name : names) {
    if (!Kind::scenario_named(name)) {
      std::string known;
      for (const std::string_view k : Kind::kScenarioNames) known += (known.empty() ? "" : ", ") + std::string(k);
      const std::string suggestion = nearest_name(name, Kind::kScenarioNames);
      return "unknown scenario \"" + name + "\"" + std::string(Kind::kScenariosFor) +
             " (one of " + known + (suggestion.empty() ? ")" : "; did you mean \"" + suggestion + "\"?)");
    }
    // Each scenario once: a list is not a way to run one scenario a thousand times.
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) return "\"" + name + "\" is listed twice";
    seen.push_back(name);
  }
  return "";
}

template <int N>
std::vector<ValidateScenarioOf<N>> scenario_list(const std::vector<std::string>& names) {
  std::vector<ValidateScenarioOf<N>> kinds;
  for (const std::string& name : names) kinds.push_back(*ValidateKindOf<N>::scenario_named(name));
  return kinds;
}

template <int N>
std::string harness_options_problem(const HarnessOptions& options) {
  if (!ValidateKindOf<N>::kTakesNoise && options.noise_counts >= 0.0) {
    return printf_string("noise: not yet for a %d-DOF environment", N);
  }
  return "";
}

#define HAPSCENE_VALIDATE_KIND(N)                                                                        \
  template std::string scenario_list_problem<N>(const std::vector<std::string>&);                        \
  template std::vector<ValidateScenarioOf<N>> scenario_list<N>(const std::vector<std::string>&); \
  template std::string harness_options_problem<N>(const HarnessOptions&);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_VALIDATE_KIND)
#undef HAPSCENE_VALIDATE_KIND

ValidationReport validate_environment(const EnvironmentOf<1>& environment, const std::vector<ScenarioKind>& kinds,
                                      HarnessOptions options) {
  options.thresholds = environment.validate;
  return validate_scene(environment.scene, kinds, options);
}

PlanarValidationReport validate_environment(const EnvironmentOf<2>& environment,
                                            const std::vector<PlanarValidateKind>& kinds, HarnessOptions options) {
  options.thresholds = environment.validate;
  try {
    return validate_planar_scene(environment.scene, kinds, options);
  } catch (const InputError& error) {
    throw InputError(environment.scene.source_path + ": a scenario cannot start where it asks (" + error.what() + ")");
  }
}

}  // namespace hapscene
