#include "engine/harness/test_spec.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/option_ranges.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/spec_judging.hpp"
#include "engine/harness/planar_test_spec.hpp"
#include "engine/harness/test_spec_parts.hpp"
#include "engine/harness/validate.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

// The step of the scan for script faults in motion (scan_faults_in_motion).
constexpr double kMotionScanStep_m = 1e-4;

// A spec, parsed and checked before anything runs.
struct ForceExpectation {
  std::string pointer;
  double x_m{}, v_m_per_s{}, force_N{}, tolerance_N{};
};
struct ScenarioExpectation {
  std::string pointer;
  ScenarioKind kind{};
  std::optional<int> min_half_cycles, max_half_cycles;
  std::optional<std::pair<double, double>> frequency_Hz;
  std::optional<double> max_force_N;
  std::optional<bool> pass;
  std::vector<std::string> fail;  // checks that must fail
};
struct Spec {
  std::string environment_path;
  HarnessOptions options;
  std::string start_pointer;  // "/options/start" when the spec sets it
  std::vector<ForceExpectation> forces;
  std::optional<std::pair<double, double>> zero_outside_m;
  std::optional<double> never_exceeds_N;
  std::optional<bool> passes_validate;
  std::vector<ScenarioExpectation> scenarios;
};

// Defined below parse_options' first use.
void refuse_planar_form(ObjectReader& r, std::string_view key, const char* expected);

HarnessOptions parse_options(ObjectReader& r) {
  HarnessOptions o;
  parse_hand_options(r, &o);
  refuse_planar_form(r, "start", "a number in m (or a string with a unit)");
  o.free_start_m = quantity_in(r, "start", value_range::free_start, o.free_start_m);
  r.finish();
  return o;
}

// A 2-D spec's form of a key (a vector or a region) in a spec for a 1-DOF environment:
// refused naming the 1-D form, before the generic "expected a number" would.
void refuse_planar_form(ObjectReader& r, std::string_view key, const char* expected) {
  const nlohmann::json* value = r.get(key);
  const bool planar_form = key == "zero_outside" ? value != nullptr && value->is_object()
                                                 : value != nullptr && value->is_array();
  if (planar_form) {
    r.fail(key, std::string("a 2-D spec's form (") + (value->is_array() ? "an array" : "an object") +
                    "): this spec's environment is 1-DOF, so \"" + std::string(key) + "\" takes " + expected);
  }
}

ScenarioExpectation parse_scenario(ObjectReader& r) {
  ScenarioExpectation e;
  e.pointer = r.pointer();
  const std::string name = r.choice("scenario", {"sweep", "press", "release", "hold", "shake", "free"});
  e.kind = *scenario_kind_named(name);
  parse_scenario_expectation_keys(r, kCheckNames, "check", &e);
  r.finish();
  return e;
}

Spec parse_spec(const std::string& path) {
  const nlohmann::json root = read_json_file(path);
  ObjectReader r(root, "", path);
  Spec spec;
  spec.environment_path = spec_environment_path(r, path);
  r.string_or("description", "");

  if (const nlohmann::json* options = r.get("options")) {
    ObjectReader o(*options, r.pointer_to("options"), path);
    spec.options = parse_options(o);
    if (o.has("start")) spec.start_pointer = o.pointer_to("start");
  }
  for_each_object_in(r, "forces", [&](ObjectReader& f) {
    ForceExpectation e;
    e.pointer = f.pointer();
    if (f.has("at")) {
      f.fail("at", "a 2-D spec's form: this spec's environment is 1-DOF, so a point is \"x\": X (a number in m "
                   "or a string with a unit)");
    }
    refuse_planar_form(f, "x", "a number in m (or a string with a unit)");
    refuse_planar_form(f, "v", "a number in m/s (or a string with a unit)");
    refuse_planar_form(f, "force", "a number in N (or a string with a unit)");
    e.x_m = quantity_in(f, "x", value_range::probe_position, std::nullopt);
    e.v_m_per_s = quantity_in(f, "v", value_range::probe_velocity, 0.0);
    e.force_N = f.quantity("force", Quantity::force_N);
    e.tolerance_N = f.quantity_or("tolerance", Quantity::force_N, 1e-6, Bound::non_negative);
    f.finish();
    spec.forces.push_back(e);
  });
  refuse_planar_form(r, "zero_outside", "[a, b], an interval of lengths");
  if (r.has("zero_outside")) spec.zero_outside_m = r.range("zero_outside", Quantity::length_m);
  else r.get("zero_outside");
  if (r.has("never_exceeds")) spec.never_exceeds_N = r.quantity("never_exceeds", Quantity::force_N, Bound::positive);
  else r.get("never_exceeds");
  spec.passes_validate = optional_bool(r, "passes_validate");
  for_each_object_in(r, "scenarios", [&](ObjectReader& e) { spec.scenarios.push_back(parse_scenario(e)); });
  r.finish();
  return spec;
}

const ScenarioResult* find_result(const ValidationReport& report, ScenarioKind kind) {
  for (const ScenarioResult& s : report.scenarios) {
    if (s.scenario.kind == kind) return &s;
  }
  return nullptr;
}

// The spec's environment has two axes (a planar profile). Anything that cannot be read
// here is left to the 1-D path, which reports it as it always has.
bool names_planar_environment(const std::string& spec_path) {
  try {
    const nlohmann::json root = read_json_file(spec_path);
    ObjectReader r(root, "", spec_path);
    return environment_axes(spec_environment_path(r, spec_path)) == 2;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

std::string spec_environment_path(ObjectReader& spec, const std::string& spec_path) {
  const std::filesystem::path path(spec_path);
  std::string stem = path.filename().string();
  stem = stem.substr(0, stem.size() - std::string(".test.json").size());
  const auto beside = [&](const std::string& name) { return (path.parent_path() / name).lexically_normal(); };
  const auto exists = [](const std::filesystem::path& file) {
    std::error_code error;
    return std::filesystem::exists(file, error);
  };
  // The other form of the same environment: a script (.lua) for a .json, and back.
  const auto other_form = [](std::filesystem::path file) {
    return file.replace_extension(file.extension() == ".lua" ? ".json" : ".lua");
  };
  if (!spec.has("environment")) {
    // NAME.test.json tests NAME.json, or the script NAME.lua when that is what is there.
    const std::filesystem::path json = beside(stem + ".json");
    return (exists(json) || !exists(other_form(json)) ? json : other_form(json)).string();
  }
  const std::string environment = spec.string("environment");
  const std::filesystem::path named = beside(environment);
  if (!exists(named) && exists(other_form(named))) {
    spec.fail("environment", "\"" + environment + "\" does not exist (did you mean \"" +
                                 std::filesystem::path(environment).replace_extension(other_form(named).extension()).string() +
                                 "\", beside it?)");
  }
  return named.string();
}

double quantity_in(ObjectReader& r, std::string_view key, const ValueRange& range, std::optional<double> fallback) {
  const double value = fallback ? r.quantity_or(key, range.quantity, *fallback) : r.quantity(key, range.quantity);
  if (r.has(key)) {
    const std::string problem = range_problem(range, value);
    if (!problem.empty()) r.fail(key, problem);
  }
  return value;
}

std::optional<bool> optional_bool(ObjectReader& r, std::string_view key) {
  const nlohmann::json* value = r.get(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_boolean()) r.fail(key, "expected true or false, got " + json_type_name(*value));
  return value->get<bool>();
}

void parse_hand_options(ObjectReader& r, HarnessOptions* o) {
  o->hand_stiffness_N_per_m = quantity_in(r, "hand_stiffness", value_range::hand_stiffness, o->hand_stiffness_N_per_m);
  o->hand_damping_N_s_per_m = quantity_in(r, "hand_damping", value_range::hand_damping, o->hand_damping_N_s_per_m);
  o->hand_mass_kg = quantity_in(r, "hand_mass", value_range::hand_mass, o->hand_mass_kg);
  o->noise_counts = quantity_in(r, "noise", value_range::noise, o->noise_counts);
  if (r.has("seed")) o->seed = static_cast<std::uint64_t>(r.integer("seed", 0, 1LL << 53));
  else r.get("seed");
}

void SpecOutcomes::add(std::string what, bool pass, std::string message) {
  result_->outcomes.push_back({std::move(what), pass, std::move(message)});
  result_->pass = result_->pass && pass;
}

void SpecOutcomes::add_fault(const std::string& message, const std::string& line) {
  const std::size_t before = seen_.lines().size();
  seen_.add(message, "");
  if (seen_.lines().size() > before && !faults_expected_) add("/environment", false, "script fault: " + line);
}

void SpecOutcomes::add_faults(const ScriptFaultLog& log) {
  for (std::size_t i = 0; i < log.lines().size(); ++i) add_fault(log.messages()[i], log.lines()[i]);
}

namespace {

// A 1-DOF spec, judged into `out`.
void run_capstan_test_spec(const std::string& spec_path, SpecResult* out) {
  const Spec spec = parse_spec(spec_path);
  SpecResult& result = *out;
  result.environment_path = spec.environment_path;
  // The environment, and everything its content can make invalid, named from the spec's
  // "/environment" (the message itself names the environment file and the place).
  const std::string referrer = spec_path + ": /environment: ";
  std::optional<Environment> loaded;
  try {
    loaded.emplace(load_environment(spec.environment_path));
    require_sampleable_workspace(loaded->scene);
  } catch (const InputError& error) {
    throw InputError(referrer + error.what());
  }
  const Scene& scene = loaded->scene;
  // The spec's options, judged by the environment's own thresholds.
  HarnessOptions options = spec.options;
  options.thresholds = loaded->validate;
  // The free scenario's start: where this environment's device can start counting.
  const bool needs_runs = spec.never_exceeds_N || spec.passes_validate || !spec.scenarios.empty();
  if (!spec.start_pointer.empty() || needs_runs) {
    const std::string problem = free_start_problem(scene, options);
    if (!problem.empty() && !spec.start_pointer.empty()) {
      throw InputError(located_message(spec_path, spec.start_pointer, problem));
    }
    if (!problem.empty()) throw InputError(referrer + scene.source_path + ": the free scenario's default start: " + problem);
  }
  OpenLoop open_loop(scene);
  SpecOutcomes spec_outcomes(&result, expects_script_failure(spec.scenarios));
  const auto add = spec_outcomes.adder();

  // Scripts too slow for the loop: nothing else is evaluated (it would take hours).
  if (const std::optional<CheckResult> pace = check_script_pace(scene)) {
    add("/environment", false, pace->detail);
    return;
  }

  // Forces at given positions and velocities.
  for (const ForceExpectation& e : spec.forces) {
    const double got_N = open_loop.output_N(e.x_m, open_loop.force_N(e.x_m, e.v_m_per_s));
    add(e.pointer, std::abs(got_N - e.force_N) <= e.tolerance_N,
        printf_string("force at x %g mm, v %g m/s: expected %g N +/- %g N, got %.6g N", e.x_m * 1e3,
                      e.v_m_per_s, e.force_N, e.tolerance_N, got_N));
  }

  // Zero outside [a, b]: every 0.1 mm of the workspace, at rest and at +/-0.1 m/s.
  if (spec.zero_outside_m) {
    const auto [a_m, b_m] = *spec.zero_outside_m;
    std::vector<double> outside_m;
    for (double x_m = scene.safety.workspace_min_m; x_m <= scene.safety.workspace_max_m; x_m += 1e-4) {
      if (x_m < a_m || x_m > b_m) outside_m.push_back(x_m);
    }
    std::string first_bad;
    for (const double v : {0.0, -0.1, 0.1}) {
      const std::vector<double> force_N = open_loop.scan(outside_m, v).force_N;
      for (std::size_t i = 0; i < outside_m.size() && first_bad.empty(); ++i) {
        const double f_N = open_loop.output_N(outside_m[i], force_N[i]);
        if (f_N != 0.0) first_bad = printf_string("%.6g N at x %.2f mm, v %g m/s", f_N, outside_m[i] * 1e3, v);
      }
    }
    add("/zero_outside", first_bad.empty(),
        printf_string("force zero outside [%g, %g] mm: ", a_m * 1e3, b_m * 1e3) +
            (first_bad.empty() ? std::string("yes") : "no, " + first_bad));
  }

  // A script fault fails the spec, with its message, unless a scenario expects the
  // "script" check to fail (SpecOutcomes). Each fault once: those of the points asked,
  // then of the whole workspace open loop (a fault no expectation reaches still fails the
  // spec), then of the runs.
  spec_outcomes.add_faults(open_loop.faults());

  // Everything that needs closed-loop runs: one validation of all scenarios.
  // Last, the faults met in motion or after some time, which the scan at rest misses
  // (every kMotionScanStep_m of the workspace).
  const auto add_motion_faults = [&] {
    if (scene.script_count == 0) return;
    std::vector<double> grid_m;
    const double span_m = scene.safety.workspace_max_m - scene.safety.workspace_min_m;
    const auto steps = static_cast<std::size_t>(std::floor(span_m / kMotionScanStep_m + 1e-9));
    for (std::size_t i = 0; i <= steps; ++i) {
      grid_m.push_back(scene.safety.workspace_min_m + static_cast<double>(i) * kMotionScanStep_m);
    }
    spec_outcomes.add_faults(scan_faults_in_motion(scene, grid_m));
  };
  if (!needs_runs) {
    if (scene.script_count > 0) spec_outcomes.add_faults(scan_force_field(scene, options.thresholds.stiff_threshold_N_per_m).faults);
    add_motion_faults();
    return;
  }
  std::optional<ValidationReport> validated;
  try {
    validated.emplace(validate_scene(scene, {}, options));
  } catch (const InputError& error) {
    throw InputError(referrer + error.what());
  }
  const ValidationReport& report = *validated;
  // Validate's scans found the scripts too slow for the loop's checks: as a scan here.
  for (const CheckResult& check : report.scene_checks) {
    if (check.name == "pace" && !check.pass) throw ScriptsTooSlow(check);
  }
  spec_outcomes.add_faults(report.field.faults);
  for (const ScenarioResult& s : report.scenarios) {
    for (const auto& f : s.metrics.script_faults) spec_outcomes.add_fault(f.message, f.text() + " in the " + s.scenario.name + " run");
  }
  add_motion_faults();

  if (spec.never_exceeds_N) {
    double largest_N = 0.0;
    std::string where;
    for (const ScenarioResult& s : report.scenarios) {
      if (s.scenario.applicable && s.metrics.max_output_N > largest_N) {
        largest_N = s.metrics.max_output_N;
        where = s.scenario.name;
      }
    }
    add("/never_exceeds", largest_N <= *spec.never_exceeds_N,
        printf_string("never exceeds %g N: largest %.4g N", *spec.never_exceeds_N, largest_N) +
            (where.empty() ? "" : " (" + where + ")"));
  }
  if (spec.passes_validate) {
    const std::string failed = failed_checks_text(report.scene_checks, report.scenarios);
    add("/passes_validate", report.pass == *spec.passes_validate,
        std::string(*spec.passes_validate ? "passes validate: " : "fails validate: ") +
            (failed.empty() ? "every check passed" : "failed " + failed));
  }

  // Expected behaviour per scenario.
  for (const ScenarioExpectation& e : spec.scenarios) {
    const ScenarioResult* s = find_result(report, e.kind);
    const std::string name(kScenarioNames[static_cast<int>(e.kind)]);
    if (s == nullptr || !s->scenario.applicable) {
      add(e.pointer, false, name + ": not applicable to this environment");
      continue;
    }
    judge_scenario_expectation(e, name, ScenarioSeen{s->metrics.oscillation, s->metrics.max_output_N, s->pass, s->checks}, add);
  }
}

}  // namespace

SpecResult run_test_spec(const std::string& spec_path) {
  SpecResult result;
  result.spec_path = spec_path;
  try {
    // A spec for a 2-DOF environment: its own format (planar_test_spec.cpp).
    if (names_planar_environment(spec_path)) {
      run_planar_test_spec(spec_path, &result);
    } else {
      run_capstan_test_spec(spec_path, &result);
    }
  } catch (const ScriptsTooSlow& slow) {
    // Scripts an open-loop scan found too slow for the loop's checks (ScanPace): the spec
    // fails with the pace message alone, as when their first calls are too slow.
    result.outcomes.clear();
    result.pass = true;
    SpecOutcomes(&result, false).add("/environment", false, slow.what());
  }
  return result;
}

std::vector<std::string> find_test_specs(const std::vector<std::string>& folders) {
  std::vector<std::string> specs;
  for (const std::string& folder : folders) {
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error)) continue;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(
             folder, std::filesystem::directory_options::skip_permission_denied, error)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_regular_file() && name.size() > 10 && name.ends_with(".test.json")) {
        specs.push_back(entry.path().lexically_normal().string());
      }
    }
  }
  std::sort(specs.begin(), specs.end());
  return specs;
}

}  // namespace hapscene
