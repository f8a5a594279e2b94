#pragma once
// Test specs per device kind (docs/reference/test-specs.md): a spec is read and judged by
// code written once over N (parse_spec here, run_test_spec in test_spec.cpp), and a kind
// brings only what its format and its open-loop checks differ in, as SpecKindOf<N>:
// - the form of a force expectation (1-D "x", "v", "force" numbers; 2-D "at", "v",
//   "force" vectors) and of "zero_outside" (an interval; a box region),
// - the form of "options/start" (a length; a point), the options its simulator refuses,
// - its scenario and check names,
// and run_spec, an overload per kind: the open-loop checks and scans over its workspace,
// then validate's runs judged alike (judge_closed_loop, spec_judging.hpp). Capstan specs
// are in capstan_test_spec.cpp, planar ones in planar_test_spec.cpp. Internal to the
// harness.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/harness/checks.hpp"
#include "engine/harness/planar_checks.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/harness/spec_judging.hpp"
#include "engine/harness/test_spec.hpp"
#include "engine/harness/test_spec_parts.hpp"
#include "engine/harness/validate.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

template <int N>
struct SpecKindOf;

// One axis (the capstan devices).
template <>
struct SpecKindOf<1> {
  struct Force {
    std::string pointer;
    double x_m{}, v_m_per_s{}, force_N{}, tolerance_N{};
  };
  using Region = std::pair<double, double>;  // [a, b] in m
  static Force parse_force(ObjectReader& f);
  static std::optional<Region> parse_zero_outside(ObjectReader& r);
  // The hand's options and "start" (a length), into `options`; finishes `o`.
  static void parse_options(ObjectReader& o, HarnessOptions* options);
  // The scenario's name, one of the six of 1-D validate.
  static std::string parse_scenario_name(ObjectReader& r);
  static constexpr const auto& kCheckNames = hapscene::kCheckNames;
  static constexpr const char* kCheckNoun = "check";
  // "never_exceeds" is judged over validate's runs (in 2-D, over the workspace open loop).
  static constexpr bool kNeverExceedsFromRuns = true;
};

// Two axes (the planar linkages).
template <>
struct SpecKindOf<2> {
  struct Force {
    std::string pointer;
    Vec2 x_m{}, v_m_per_s{}, force_N{};
    double tolerance_N{};
  };
  struct Region {
    Vec2 min_m{}, max_m{};
    bool contains(const Vec2& p) const {
      return p[0] >= min_m[0] && p[0] <= max_m[0] && p[1] >= min_m[1] && p[1] <= max_m[1];
    }
  };
  static Force parse_force(ObjectReader& f);
  static std::optional<Region> parse_zero_outside(ObjectReader& r);
  // The hand's options and "start" (a point), into `options`; "noise" is refused (the
  // planar simulator's sensors have no noise model yet). Finishes `o`.
  static void parse_options(ObjectReader& o, HarnessOptions* options);
  // The scenario's name, one of the seven of 2-D validate.
  static std::string parse_scenario_name(ObjectReader& r);
  static constexpr const auto& kCheckNames = kPlanarCheckNames;
  static constexpr const char* kCheckNoun = "2-D check";
  static constexpr bool kNeverExceedsFromRuns = false;
};

// A spec, parsed and checked before anything runs.
template <int N>
struct SpecOf {
  using Kind = SpecKindOf<N>;
  std::string environment_path;
  HarnessOptions options;     // "options": the hand, noise, seed and the free scenario's start
  std::string start_pointer;  // "/options/start" when the spec sets it
  std::vector<typename Kind::Force> forces;
  std::optional<typename Kind::Region> zero_outside_m;
  std::optional<double> never_exceeds_N;
  std::optional<bool> passes_validate;
  std::vector<ScenarioExpectation> scenarios;

  // Whether judging the spec runs validate's scenarios (closed loop).
  bool needs_runs() const {
    return passes_validate || !scenarios.empty() || (never_exceeds_N && Kind::kNeverExceedsFromRuns);
  }
};

// Reads the spec `root` (the JSON of the file at `path`) for an environment of N axes
// (InputError, located, for anything invalid in it). The keys are read in the order the
// format lists them, so the first problem of a spec is the one reported, in every kind.
template <int N>
SpecOf<N> parse_spec(const nlohmann::json& root, const std::string& path) {
  using Kind = SpecKindOf<N>;
  ObjectReader r(root, "", path);
  SpecOf<N> spec;
  spec.environment_path = spec_environment_path(r, path);
  r.string_or("description", "");
  if (const nlohmann::json* options = r.get("options")) {
    ObjectReader o(*options, r.pointer_to("options"), path);
    Kind::parse_options(o, &spec.options);
    if (o.has("start")) spec.start_pointer = o.pointer_to("start");
  }
  for_each_object_in(r, "forces", [&](ObjectReader& f) { spec.forces.push_back(Kind::parse_force(f)); });
  spec.zero_outside_m = Kind::parse_zero_outside(r);
  if (r.has("never_exceeds")) spec.never_exceeds_N = r.quantity("never_exceeds", Quantity::force_N, Bound::positive);
  else r.get("never_exceeds");
  spec.passes_validate = optional_bool(r, "passes_validate");
  for_each_object_in(r, "scenarios", [&](ObjectReader& s) {
    ScenarioExpectation e;
    e.pointer = s.pointer();
    e.scenario = Kind::parse_scenario_name(s);
    parse_scenario_expectation_keys(s, Kind::kCheckNames, Kind::kCheckNoun, &e);
    s.finish();
    spec.scenarios.push_back(std::move(e));
  });
  r.finish();
  return spec;
}

// Refuses a free scenario's start the device cannot take (free_start_problem), when the
// spec sets one (at its "/options/start") or its runs need the default one (named from the
// spec's "/environment": the environment's device cannot start where validate starts it).
template <int N>
void check_free_start(const std::string& spec_path, const SpecOf<N>& spec, const EnvironmentOf<N>& environment) {
  if (spec.start_pointer.empty() && !spec.needs_runs()) return;
  HarnessOptions options = spec.options;
  options.thresholds = environment.validate;
  const std::string problem = free_start_problem(environment.scene, options);
  if (problem.empty()) return;
  if (!spec.start_pointer.empty()) throw InputError(located_message(spec_path, spec.start_pointer, problem));
  throw InputError(spec_path + ": /environment: " + environment.scene.source_path +
                   ": the free scenario's default start: " + problem);
}

// Judges `spec` on `environment` (loaded from spec.environment_path) into `result`:
// InputError, located from the spec's "/environment", for what the environment's content
// makes invalid; ScriptsTooSlow when a scan finds the scripts too slow for the loop's
// checks.
void run_spec(const std::string& spec_path, const SpecOf<1>& spec, const EnvironmentOf<1>& environment, SpecResult* result);
void run_spec(const std::string& spec_path, const SpecOf<2>& spec, const EnvironmentOf<2>& environment, SpecResult* result);

}  // namespace hapscene
