// Test specs of 2-DOF (planar) environments (docs/reference/test-specs.md, "Test specs in
// 2-D"): the 1-D format with vectors (SpecKindOf<2>). `forces` at points "at": [x, y] with
// "v": [vx, vy] and "force": [fx, fy] (tolerance on the magnitude of the difference),
// `zero_outside` a box region, and `never_exceeds` over a grid of the workspace, all open
// loop as the 2-D `probe` computes them; every script fault in the workspace, at rest, in
// motion or later in time, fails the spec. Then validate's seven 2-D scenarios
// (test_spec_kind.hpp).
#include <algorithm>
#include <cmath>
#include <optional>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/units.hpp"
#include "engine/effects/vector_reader.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/planar_open_loop.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/harness/planar_validate_scenario.hpp"
#include "engine/harness/test_spec_kind.hpp"

namespace hapscene {
namespace {

// The grid the region checks and the scans for faults use: every 1 mm of the workspace
// box, on both axes.
constexpr double kPlanarSpecGridStep_m = kPlanarFaultScanStep_m;

// The velocities of the region checks (zero_outside, never_exceeds) besides rest, as the
// 1-D spec's +/-0.1 m/s, along each axis (only when the scene reads velocity).
constexpr double kRegionScanSpeed_m_per_s = 0.1;

Range range_of(const ValueRange& range) { return Range{range.min, range.max, range.min_exclusive}; }
// Any finite force component a spec may state.
constexpr Range kForceComponent_N{-1e9, 1e9};
constexpr Range kRegionComponent_m{-1000.0, 1000.0};

// A 1-D spec's form of a key in a 2-D spec: refused naming the 2-D form.
void refuse_axis_form(ObjectReader& r, std::string_view key, const std::string& expected) {
  const nlohmann::json* value = r.get(key);
  if (value != nullptr) {
    r.fail(key, "a 1-D spec's form: this spec's environment is 2-DOF (a planar profile), so " + expected);
  }
}

}  // namespace

SpecKindOf<2>::Force SpecKindOf<2>::parse_force(ObjectReader& f) {
  Force e;
  e.pointer = f.pointer();
  refuse_axis_form(f, "x", "a point is \"at\": [x, y] (lengths in m, or strings with a unit)");
  e.x_m = read_vector(f, "at", Quantity::length_m, range_of(value_range::probe_position));
  e.v_m_per_s = read_vector_or(f, "v", Quantity::velocity_m_per_s, Vec2{}, range_of(value_range::probe_velocity));
  e.force_N = read_vector(f, "force", Quantity::force_N, kForceComponent_N);
  e.tolerance_N = f.quantity_or("tolerance", Quantity::force_N, 1e-6, Bound::non_negative);
  f.finish();
  return e;
}

std::optional<SpecKindOf<2>::Region> SpecKindOf<2>::parse_zero_outside(ObjectReader& r) {
  constexpr std::string_view key = "zero_outside";
  const nlohmann::json* value = r.get(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_object()) {
    r.fail(key, "expected a region {\"min\": [x, y], \"max\": [x, y]} in a 2-D spec, got " + json_type_name(*value) +
                    (value->is_array() ? " (the 1-D form [a, b])" : ""));
  }
  ObjectReader region(*value, r.pointer_to(key), r.file());
  Region result;
  result.min_m = read_vector(region, "min", Quantity::length_m, kRegionComponent_m);
  result.max_m = read_vector(region, "max", Quantity::length_m, kRegionComponent_m);
  if (!(result.min_m[0] <= result.max_m[0] && result.min_m[1] <= result.max_m[1])) {
    region.fail("max", "must not be below \"min\" on either axis");
  }
  region.finish();
  return result;
}

void SpecKindOf<2>::parse_options(ObjectReader& o, HarnessOptions* options) {
  parse_hand_options(o, options);
  // The planar simulator's sensors have no noise model yet (validate refuses --noise too).
  if (o.has("noise")) o.fail("noise", "not yet for a 2-DOF environment");
  if (!o.has("start")) o.get("start");
  if (o.has("start")) {
    const nlohmann::json* start = o.get("start");
    if (!start->is_array()) {
      o.fail("start", "a 1-D spec's form: this spec's environment is 2-DOF, so \"start\" is [x, y]");
    }
    options->free_start_planar_m = read_vector(o, "start", Quantity::length_m, range_of(value_range::free_start));
  }
  o.finish();
}

std::string SpecKindOf<2>::parse_scenario_name(ObjectReader& r) {
  const std::string name = r.string("scenario");
  if (!planar_validate_kind_named(name)) {
    const std::string suggestion = nearest_name(name, kPlanarValidateNames);
    r.fail("scenario", "unknown 2-D scenario \"" + name + "\"" +
                           (suggestion.empty() ? "" : " (did you mean \"" + suggestion + "\"?)"));
  }
  return name;
}

namespace {

std::string mm_pair(const Vec2& x_m) { return printf_string("(%g, %g) mm", x_m[0] * 1e3, x_m[1] * 1e3); }
std::string vector_text(const Vec2& v, const char* unit, const char* format = "%g") {
  return "(" + printf_string(format, v[0]) + ", " + printf_string(format, v[1]) + ") " + unit;
}

// The velocities of a region check: rest, and +/-0.1 m/s along each axis when the scene
// reads velocity.
std::vector<Vec2> region_velocities(const PlanarScene& scene) {
  std::vector<Vec2> velocities{Vec2{}};
  if (!scene.needs.velocity) return velocities;
  for (const double s : {kRegionScanSpeed_m_per_s, -kRegionScanSpeed_m_per_s}) {
    velocities.push_back(Vec2{{s, 0.0}});
    velocities.push_back(Vec2{{0.0, s}});
  }
  return velocities;
}

}  // namespace

void run_spec(const std::string& spec_path, const SpecOf<2>& spec, const EnvironmentOf<2>& environment, SpecResult* out) {
  SpecResult& result = *out;
  const std::string referrer = spec_path + ": /environment: ";
  const PlanarScene& scene = environment.scene;
  check_free_start(spec_path, spec, environment);
  SpecOutcomes spec_outcomes(&result, expects_script_failure(spec.scenarios));
  const auto add = spec_outcomes.adder();
  // Budget errors (a script whose top level is slow) name the spec's environment.
  const auto located = [&](auto&& work) {
    try {
      work();
    } catch (const InputError& error) {
      throw InputError(referrer + error.what());
    }
  };

  // Scripts too slow for the loop: nothing else is evaluated.
  if (const std::optional<CheckResult> pace = check_script_pace(scene)) {
    add("/environment", false, pace->detail);
    return;
  }

  // A script fault fails the spec unless a scenario expects the "script" check to fail
  // (SpecOutcomes).
  // Forces at given points and velocities, each from fresh instances. One open loop (one
  // creation budget) for them and the region checks.
  PlanarOpenLoop open_loop(scene);
  for (const SpecKindOf<2>::Force& e : spec.forces) {
    Vec2 got_N{};
    located([&] { got_N = open_loop.output_N(e.x_m, open_loop.force_N(e.x_m, e.v_m_per_s)); });
    const double off_N = norm(got_N - e.force_N);
    add(e.pointer, off_N <= e.tolerance_N,
        "force at " + mm_pair(e.x_m) + ", v " + vector_text(e.v_m_per_s, "m/s") + ": expected " +
            vector_text(e.force_N, "N") + printf_string(" +/- %g N, got ", e.tolerance_N) +
            vector_text(got_N, "N", "%.6g") + printf_string(" (off by %.3g N)", off_N));
  }

  // The region checks scan the workspace grid once per velocity.
  const std::vector<Vec2> grid = planar_workspace_grid(scene, kPlanarSpecGridStep_m);
  if (spec.zero_outside_m || spec.never_exceeds_N) {
    std::string first_nonzero;
    double largest_N = 0.0;
    std::string largest_where;
    const SpecKindOf<2>::Region region = spec.zero_outside_m.value_or(SpecKindOf<2>::Region{});
    for (const Vec2& v : region_velocities(scene)) {
      PlanarOpenLoopScan scan;
      located([&] { scan = open_loop.scan(grid, v); });
      for (std::size_t i = 0; i < grid.size(); ++i) {
        const Vec2 out_N = open_loop.output_N(grid[i], scan.force_N[i]);
        const double magnitude_N = norm(out_N);
        if (spec.zero_outside_m && first_nonzero.empty() && !region.contains(grid[i]) && magnitude_N != 0.0) {
          first_nonzero = vector_text(out_N, "N", "%.6g") + " at " + mm_pair(grid[i]) + ", v " + vector_text(v, "m/s");
        }
        if (magnitude_N > largest_N) {
          largest_N = magnitude_N;
          largest_where = mm_pair(grid[i]) + ", v " + vector_text(v, "m/s");
        }
      }
    }
    if (spec.zero_outside_m) {
      add("/zero_outside", first_nonzero.empty(),
          "force zero outside the box from " + mm_pair(region.min_m) + " to " + mm_pair(region.max_m) +
              printf_string(" (every %g mm of the workspace): ", kPlanarSpecGridStep_m * 1e3) +
              (first_nonzero.empty() ? std::string("yes") : "no, " + first_nonzero));
    }
    if (spec.never_exceeds_N) {
      add("/never_exceeds", largest_N <= *spec.never_exceeds_N,
          printf_string("never exceeds %g N (every %g mm of the workspace): largest %.4g N", *spec.never_exceeds_N,
                        kPlanarSpecGridStep_m * 1e3, largest_N) +
              (largest_where.empty() ? "" : " at " + largest_where));
    }
  }

  spec_outcomes.add_faults(open_loop.faults());

  // Faults anywhere in the workspace, at rest, in motion and later in time.
  if (scene.script_count > 0) {
    ScriptFaultLog motion;
    located([&] { motion = scan_planar_faults_in_motion(scene, grid); });
    spec_outcomes.add_faults(motion);
  }

  // Closed-loop expectations: one run of 2-D validate (all seven scenarios) with the
  // spec's options and the environment's "validate" thresholds.
  if (!spec.passes_validate && spec.scenarios.empty()) return;
  HarnessOptions options = spec.options;
  options.thresholds = environment.validate;
  std::optional<PlanarValidationReport> validated;
  located([&] { validated.emplace(validate_planar_scene(scene, {}, options)); });
  const PlanarValidationReport& report = *validated;
  for (const PlanarScenarioResult& s : report.scenarios) {
    for (const auto& f : s.metrics.script_faults) spec_outcomes.add_fault(f.message, f.text() + " in the " + s.scenario.name + " run");
  }
  judge_closed_loop(report, spec.passes_validate, spec.scenarios, add);
}

}  // namespace hapscene
