#pragma once
// `validate` per device kind: the types and names in which the capstan's validate
// (validate.hpp) and the planar linkages' (planar_validate.hpp) differ, so that the
// command, the live view, the test specs and Python run validate with code written once
// over N (as engine/cli/run_kind.hpp does for `run`). Each kind's report functions are
// overloads on its report type (report.hpp and figures.hpp, planar_report.hpp). A new kind adds a
// specialisation of ValidateKindOf and its overloads of validate_environment and of the
// report functions.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/harness/figures.hpp"
#include "engine/harness/planar_report.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/harness/report.hpp"
#include "engine/harness/validate.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

template <int N>
struct ValidateKindOf;

// One axis: the capstan devices (the Hapkit), validate.hpp's six scenarios.
template <>
struct ValidateKindOf<1> {
  using Scenario = ScenarioKind;
  using Report = ValidationReport;
  static constexpr std::span<const std::string_view> kScenarioNames{hapscene::kScenarioNames};
  static std::optional<Scenario> scenario_named(std::string_view name) { return scenario_kind_named(name); }
  // Said after an unknown scenario's name (scenario_list_problem): nothing, the first kind.
  static constexpr std::string_view kScenariosFor = "";
  // The simulated sensors take --noise (the profile's noise otherwise).
  static constexpr bool kTakesNoise = true;
  // The free scenario's start (--start X).
  using Point = double;
  static void set_free_start(HarnessOptions* options, double x_m) { options->free_start_m = x_m; }
};

// Two axes: the planar linkages, planar_validate.hpp's seven scenarios.
template <>
struct ValidateKindOf<2> {
  using Scenario = PlanarValidateKind;
  using Report = PlanarValidationReport;
  static constexpr std::span<const std::string_view> kScenarioNames{kPlanarValidateNames};
  static std::optional<Scenario> scenario_named(std::string_view name) { return planar_validate_kind_named(name); }
  static constexpr std::string_view kScenariosFor = " for a 2-DOF environment";
  // The planar simulator's sensors have no noise model yet: --noise is refused, not ignored.
  static constexpr bool kTakesNoise = false;
  // The free scenario's start (--start X,Y).
  using Point = Vec2;
  static void set_free_start(HarnessOptions* options, const Vec2& x_m) { options->free_start_planar_m = x_m; }
};

template <int N>
using ValidateScenarioOf = typename ValidateKindOf<N>::Scenario;
template <int N>
using ValidationReportOf = typename ValidateKindOf<N>::Report;

// What is wrong with the scenario list `names` for a scene of N axes ("" when nothing): a
// name the kind does not know ("unknown scenario \"swep\" (one of sweep, press, ...; did
// you mean \"sweep\"?)"; in 2-D "... for a 2-DOF environment (one of ...") or a name given
// twice ("\"hold\" is listed twice"). Each caller puts its own prefix on it.
template <int N>
std::string scenario_list_problem(const std::vector<std::string>& names);

// The scenarios `names` lists, in order (empty: all of them); the list must have no
// problem (scenario_list_problem).
template <int N>
std::vector<ValidateScenarioOf<N>> scenario_list(const std::vector<std::string>& names);

// What is wrong with `options` for a scene of N axes ("" when nothing): "noise: not yet
// for a 2-DOF environment" (the caller's prefix before it, "--" on the command line).
template <int N>
std::string harness_options_problem(const HarnessOptions& options);

// Validate on a loaded environment: its "validate" block as the thresholds over
// `options`, the scenarios `kinds` (all when empty). Throws InputError naming the
// environment's file when a scenario cannot start where it asks.
ValidationReport validate_environment(const EnvironmentOf<1>& environment, const std::vector<ScenarioKind>& kinds,
                                      HarnessOptions options);
PlanarValidationReport validate_environment(const EnvironmentOf<2>& environment,
                                            const std::vector<PlanarValidateKind>& kinds, HarnessOptions options);

}  // namespace hapscene
