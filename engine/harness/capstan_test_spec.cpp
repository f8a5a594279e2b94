// Test specs of 1-DOF (capstan) environments (docs/reference/test-specs.md): the forms of
// their keys (SpecKindOf<1>) and their open-loop checks, every 0.1 mm of the workspace, at
// rest and at +/-0.1 m/s; then validate's six scenarios (test_spec_kind.hpp).
#include <cmath>
#include <optional>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/harness/force_field.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/option_ranges.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/test_spec_kind.hpp"
#include "engine/harness/validate_kind.hpp"

namespace hapscene {
namespace {

// The step of the scan for script faults in motion (scan_faults_in_motion).
constexpr double kMotionScanStep_m = 1e-4;

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

}  // namespace

SpecKindOf<1>::Force SpecKindOf<1>::parse_force(ObjectReader& f) {
  Force e;
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
  return e;
}

std::optional<SpecKindOf<1>::Region> SpecKindOf<1>::parse_zero_outside(ObjectReader& r) {
  refuse_planar_form(r, "zero_outside", "[a, b], an interval of lengths");
  if (r.has("zero_outside")) return r.range("zero_outside", Quantity::length_m);
  r.get("zero_outside");
  return std::nullopt;
}

void SpecKindOf<1>::parse_options(ObjectReader& o, HarnessOptions* options) {
  parse_hand_options(o, options);
  refuse_planar_form(o, "start", "a number in m (or a string with a unit)");
  options->free_start_m = quantity_in(o, "start", value_range::free_start, options->free_start_m);
  o.finish();
}

std::string SpecKindOf<1>::parse_scenario_name(ObjectReader& r) {
  return r.choice("scenario", {"sweep", "press", "release", "hold", "shake", "free"});
}

void run_spec(const std::string& spec_path, const SpecOf<1>& spec, const EnvironmentOf<1>& environment, SpecResult* out) {
  SpecResult& result = *out;
  // What the environment's content makes invalid, named from the spec's "/environment"
  // (the message itself names the environment file and the place).
  const std::string referrer = spec_path + ": /environment: ";
  try {
    require_sampleable_workspace(environment.scene);
  } catch (const InputError& error) {
    throw InputError(referrer + error.what());
  }
  const Scene& scene = environment.scene;
  check_free_start(spec_path, spec, environment);
  const bool needs_runs = spec.needs_runs();
  OpenLoop open_loop(scene);
  SpecOutcomes spec_outcomes(&result, expects_script_failure(spec.scenarios));
  const auto add = spec_outcomes.adder();

  // Scripts too slow for the loop: nothing else is evaluated (it would take hours).
  if (const std::optional<CheckResult> pace = check_script_pace(scene)) {
    add("/environment", false, pace->detail);
    return;
  }

  // Forces at given positions and velocities.
  for (const SpecKindOf<1>::Force& e : spec.forces) {
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
    if (scene.script_count > 0) spec_outcomes.add_faults(scan_force_field(scene, environment.validate.stiff_threshold_N_per_m).faults);
    add_motion_faults();
    return;
  }
  std::optional<ValidationReport> validated;
  try {
    validated.emplace(validate_environment(environment, {}, spec.options));
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
  judge_closed_loop(report, spec.passes_validate, spec.scenarios, add);
}

}  // namespace hapscene
