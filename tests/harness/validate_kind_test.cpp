// validate per device kind (engine/harness/validate_kind.hpp): the scenario lists and the
// options every caller (the command, the live view, the test specs, Python) reads the
// same way for each N of the list, and validate_environment's use of the file's
// "validate" block.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/harness/validate_kind.hpp"
#include "engine/load/environment.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

template <int N>
void check_scenario_lists() {
  using Kind = ValidateKindOf<N>;
  CAPTURE(N);
  // Every name of the kind, in its order, and back in the order asked.
  std::vector<std::string> all;
  for (const std::string_view name : Kind::kScenarioNames) all.emplace_back(name);
  CHECK(scenario_list_problem<N>(all).empty());
  const std::vector<ValidateScenarioOf<N>> kinds = scenario_list<N>(all);
  REQUIRE(kinds.size() == all.size());
  for (std::size_t i = 0; i < kinds.size(); ++i) CHECK(static_cast<std::size_t>(kinds[i]) == i);
  const std::vector<std::string> reversed(all.rbegin(), all.rend());
  CHECK(scenario_list<N>(reversed).front() == kinds.back());
  // No list: every scenario (validate's empty list).
  CHECK(scenario_list_problem<N>({}).empty());
  CHECK(scenario_list<N>({}).empty());
  // A near miss names every scenario and the nearest; a name twice is refused.
  const std::string unknown = scenario_list_problem<N>({"sweep", "hodl"});
  CHECK(unknown.find("unknown scenario \"hodl\"" + std::string(Kind::kScenariosFor) + " (one of sweep, press") == 0);
  CHECK(unknown.find("did you mean \"hold\"?)") != std::string::npos);
  for (const std::string_view name : Kind::kScenarioNames) CHECK(unknown.find(std::string(name)) != std::string::npos);
  CHECK(scenario_list_problem<N>({"hold", "free", "hold"}) == "\"hold\" is listed twice");
  CHECK(scenario_list_problem<N>({""}).find("unknown scenario \"\"") == 0);
  // --noise: taken where the kind's simulated sensors model it, refused (not ignored) elsewhere.
  HarnessOptions noisy;
  noisy.noise_counts = 1.0;
  CHECK(harness_options_problem<N>(HarnessOptions{}).empty());
  CHECK(harness_options_problem<N>(noisy).empty() == Kind::kTakesNoise);
}

}  // namespace

TEST_CASE("validate kinds: every N reads its scenario list and options the same way") {
#define HAPSCENE_CHECK_KIND(N) check_scenario_lists<N>();
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_CHECK_KIND)
#undef HAPSCENE_CHECK_KIND
  HarnessOptions noisy;
  noisy.noise_counts = 0.5;
  CHECK(harness_options_problem<2>(noisy) == "noise: not yet for a 2-DOF environment");
}

TEST_CASE("validate kinds: validate_environment judges by the file's validate block") {
  const std::string wall = test::source_path("environments/wall.json");
  const Environment shipped = load_environment(wall);
  CHECK(validate_environment(shipped, {ScenarioKind::press}, HarnessOptions{}).pass);
  // The same wall with a force limit for validate below what the press asks: fails there.
  Environment strict = shipped;
  strict.validate.max_force_N = 0.05;
  const ValidationReport report = validate_environment(strict, {ScenarioKind::press}, HarnessOptions{});
  CHECK_FALSE(report.pass);
  REQUIRE(report.scenarios.size() == 1);
  bool max_force_failed = false;
  for (const CheckResult& check : report.scenarios[0].checks) {
    if (check.name == "max_force") max_force_failed = !check.pass && check.threshold == 0.05;
  }
  CHECK(max_force_failed);
}

TEST_CASE("validate kinds: a 2-D scenario that cannot start is refused naming the file") {
  const std::string path = test::source_path("environments/planar/haplink_box_inside.json");
  const PlanarEnvironment environment = load_planar_environment(path);
  HarnessOptions options;
  options.free_start_planar_m = Vec2{{0.5, 0.5}};  // half a metre out: no pose of the linkage reaches it
  try {
    validate_environment(environment, {PlanarValidateKind::free}, options);
    FAIL("expected InputError");
  } catch (const InputError& error) {
    const std::string message = error.what();
    CHECK(message.find(path + ": a scenario cannot start where it asks (") == 0);
  }
}
