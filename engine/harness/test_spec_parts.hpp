#pragma once
// What test specs of every kind (test_spec_kind.hpp) read alike:
// the environment a spec names, quantities checked against the command line's ranges,
// optional booleans, the virtual hand's options, a scenario expectation's keys; and how
// every kind records outcomes and script faults. Internal to the harness.
#include <algorithm>
#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>

#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/units.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/option_ranges.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/harness/test_spec.hpp"

namespace hapscene {

// The environment of the spec at `spec_path`: its "environment" (relative to the spec),
// or the spec's name with ".json" for ".test.json", next to it.
std::string spec_environment_path(ObjectReader& spec, const std::string& spec_path);

// A quantity from the spec, refused (with the spec file and JSON pointer) outside the
// range the command line accepts for the same value; `fallback` when absent.
double quantity_in(ObjectReader& r, std::string_view key, const ValueRange& range, std::optional<double> fallback);

std::optional<bool> optional_bool(ObjectReader& r, std::string_view key);

// The hand's stiffness, damping and mass, the noise and the seed of "options" (not
// "start", whose form depends on the dimension), into `options`.
void parse_hand_options(ObjectReader& r, HarnessOptions* options);

// Each object of the array `key`, when the spec has it, read by `parse` (given the
// object's ObjectReader), in order; refused when `key` is not an array.
template <typename Parse>
void for_each_object_in(ObjectReader& r, std::string_view key, Parse parse) {
  const nlohmann::json* items = r.get(key);
  if (items == nullptr) return;
  if (!items->is_array()) r.fail(key, "expected an array, got " + json_type_name(*items));
  for (std::size_t i = 0; i < items->size(); ++i) {
    ObjectReader item((*items)[i], json_pointer_append(r.pointer_to(key), i), r.file());
    parse(item);
  }
}

// A scenario expectation's keys after "scenario" (min_half_cycles, max_half_cycles,
// frequency, max_force, pass, fail), into `e` (a ScenarioExpectation of either
// dimension). A name in "fail" must be one of `check_names`; an unknown one is refused as
// an "unknown <check_noun>", with the nearest name. Absent keys are still asked for, so a
// misspelt one gets a "did you mean".
template <typename Expectation, std::size_t Count>
void parse_scenario_expectation_keys(ObjectReader& r, const char* const (&check_names)[Count],
                                     const std::string& check_noun, Expectation* e) {
  if (r.has("min_half_cycles")) e->min_half_cycles = static_cast<int>(r.integer("min_half_cycles", 0, 100000));
  else r.get("min_half_cycles");
  if (r.has("max_half_cycles")) e->max_half_cycles = static_cast<int>(r.integer("max_half_cycles", 0, 100000));
  else r.get("max_half_cycles");
  if (r.has("frequency")) e->frequency_Hz = r.range("frequency", Quantity::frequency_Hz);
  else r.get("frequency");
  if (r.has("max_force")) e->max_force_N = r.quantity("max_force", Quantity::force_N, Bound::positive);
  else r.get("max_force");
  e->pass = optional_bool(r, "pass");
  if (const nlohmann::json* fail = r.get("fail")) {
    if (!fail->is_array()) r.fail("fail", "expected an array of check names, got " + json_type_name(*fail));
    for (std::size_t i = 0; i < fail->size(); ++i) {
      const nlohmann::json& item = (*fail)[i];
      const std::string pointer = json_pointer_append(r.pointer_to("fail"), i);
      if (!item.is_string()) throw InputError(located_message(r.file(), pointer, "expected a check name"));
      const std::string check = item.get<std::string>();
      if (std::find_if(std::begin(check_names), std::end(check_names),
                       [&](const char* n) { return check == n; }) == std::end(check_names)) {
        const std::string suggestion = nearest_name(check, check_names);
        throw InputError(located_message(r.file(), pointer, "unknown " + check_noun + " \"" + check + "\"" +
                                                                (suggestion.empty() ? "" : " (did you mean \"" + suggestion + "\"?)")));
      }
      e->fail.push_back(check);
    }
  }
}

// Whether a scenario expectation of `scenarios` expects the "script" check to fail.
template <typename Expectations>
bool expects_script_failure(const Expectations& scenarios) {
  return std::any_of(scenarios.begin(), scenarios.end(), [](const auto& e) {
    return std::find(e.fail.begin(), e.fail.end(), "script") != e.fail.end();
  });
}

// A spec's outcomes as they are judged, into `result` (whose pass they clear), and the
// script faults met: each message once, failing the spec ("/environment", "script fault:
// " and its line) unless `faults_expected` (a scenario expects the "script" check to fail).
class SpecOutcomes {
 public:
  SpecOutcomes(SpecResult* result, bool faults_expected) : result_(result), faults_expected_(faults_expected) {}
  void add(std::string what, bool pass, std::string message);
  void add_fault(const std::string& message, const std::string& line);
  void add_faults(const ScriptFaultLog& log);
  // `add` as a callable, for judge_scenario_expectation.
  auto adder() {
    return [this](std::string what, bool pass, std::string message) { add(std::move(what), pass, std::move(message)); };
  }

 private:
  SpecResult* result_;
  bool faults_expected_;
  ScriptFaultLog seen_;
};

}  // namespace hapscene
