#include "engine/harness/force_field.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/harness/pace.hpp"

namespace hapscene {

double ForceField::potential_at_J(double x_m) const noexcept {
  if (potential_J.empty()) return 0.0;
  const double position = (x_m - min_m) / step_m;
  if (position <= 0.0) return potential_J.front();
  const auto last = static_cast<double>(potential_J.size() - 1);
  if (position >= last) return potential_J.back();
  const auto i = static_cast<std::size_t>(position);
  const double fraction = position - static_cast<double>(i);
  return potential_J[i] + fraction * (potential_J[i + 1] - potential_J[i]);
}

double ForceField::penetration_m(double x_m) const noexcept {
  double depth_m = 0.0;
  for (const StiffRegion& region : regions) {
    if (x_m < region.low_m || x_m > region.high_m) continue;
    double from_edge_m = INFINITY;
    if (region.low_is_edge) from_edge_m = std::min(from_edge_m, x_m - region.low_m);
    if (region.high_is_edge) from_edge_m = std::min(from_edge_m, region.high_m - x_m);
    if (std::isfinite(from_edge_m)) depth_m = std::max(depth_m, from_edge_m);
  }
  return depth_m;
}

void require_sampleable_workspace(const Scene& scene) {
  constexpr double step_m = kFieldStep_m;
  const double span_m = scene.safety.workspace_max_m - scene.safety.workspace_min_m;
  const double max_span_m = static_cast<double>(kMaxFieldPoints - 1) * step_m;
  if (std::isfinite(span_m) && span_m <= max_span_m * (1.0 + 1e-9)) return;
  throw InputError(printf_string(
      "%s: /device: %s: the workspace [%g, %g] m spans %g m; the harness samples it every %g um "
      "and takes at most %g m",
      scene.source_path.c_str(), scene.device_file.c_str(), scene.safety.workspace_min_m,
      scene.safety.workspace_max_m, span_m, step_m * 1e6, max_span_m));
}

namespace {

// The field on `field`'s grid (min_m and step_m set); throws ScriptsTooSlow when the
// scan finds the scripts too slow for the loop's checks.
ForceField sample_field(const Scene& scene, double stiff_threshold_N_per_m, ForceField field) {
  const double step_m = field.step_m;
  const double span_m = scene.safety.workspace_max_m - field.min_m;
  const auto points = static_cast<std::size_t>(std::floor(span_m / step_m)) + 1;

  // Sample the field at rest, before and after the static safety rules, each point as
  // fresh script instances give it.
  OpenLoop open_loop(scene);
  std::vector<double> x_m(points);
  for (std::size_t i = 0; i < points; ++i) x_m[i] = field.min_m + static_cast<double>(i) * step_m;
  OpenLoopScan scan = open_loop.scan(x_m, 0.0, false);
  field.faults = open_loop.faults();
  field.behaviour = scan.behaviour;

  // A script with state or time has no fixed field: no walls are inferred from it. The
  // energy it stores is estimated from the field fresh instances render at rest (a
  // virtual mass settled where the handle is), on a grid of at most 201 points.
  if (!field.behaviour.static_field()) {
    const std::size_t coarse_points = std::min<std::size_t>(points, 201);
    const double coarse_step_m = coarse_points > 1 ? span_m / static_cast<double>(coarse_points - 1) : step_m;
    std::vector<double> coarse_x_m(coarse_points);
    for (std::size_t i = 0; i < coarse_points; ++i) coarse_x_m[i] = field.min_m + static_cast<double>(i) * coarse_step_m;
    const OpenLoopScan coarse = open_loop.scan(coarse_x_m, 0.0, true);
    field.faults = open_loop.faults();
    std::vector<double> coarse_J(coarse_points, 0.0);
    for (std::size_t i = 1; i < coarse_points; ++i) {
      coarse_J[i] = coarse_J[i - 1] - 0.5 *
                                          (open_loop.output_N(coarse_x_m[i - 1], coarse.force_N[i - 1]) +
                                           open_loop.output_N(coarse_x_m[i], coarse.force_N[i])) *
                                          coarse_step_m;
    }
    field.potential_J.resize(points);
    for (std::size_t i = 0; i < points; ++i) {
      const double position = coarse_points > 1 ? (x_m[i] - field.min_m) / coarse_step_m : 0.0;
      const std::size_t j = std::min(static_cast<std::size_t>(position), coarse_points > 1 ? coarse_points - 2 : 0);
      const double fraction = coarse_points > 1 ? position - static_cast<double>(j) : 0.0;
      field.potential_J[i] =
          coarse_points > 1 ? coarse_J[j] + fraction * (coarse_J[j + 1] - coarse_J[j]) : 0.0;
    }
    return field;
  }
  field.force_N.reserve(points);
  field.output_N.reserve(points);
  for (std::size_t i = 0; i < points; ++i) {
    const double raw_N = scan.force_N[i];
    field.force_N.push_back(std::isfinite(raw_N) ? raw_N : 0.0);
    field.output_N.push_back(open_loop.output_N(x_m[i], raw_N));
  }

  // Stored energy: U(x) = -integral of F dx (trapezoids), 0 at the workspace's low end.
  field.potential_J.assign(points, 0.0);
  for (std::size_t i = 1; i < points; ++i) {
    field.potential_J[i] =
        field.potential_J[i - 1] - 0.5 * (field.output_N[i - 1] + field.output_N[i]) * step_m;
  }

  // Stiff regions: runs of grid cells where -dF/dx reaches the threshold (a jump in the
  // field is a cell of huge stiffness). Gaps of one cell are bridged.
  const auto stiffness_of = [&](std::size_t i) {
    return -(field.force_N[i + 1] - field.force_N[i]) / step_m;
  };
  std::size_t i = 0;
  while (i + 1 < points) {
    if (stiffness_of(i) < stiff_threshold_N_per_m) {
      ++i;
      continue;
    }
    StiffRegion region;
    region.low_m = field.min_m + static_cast<double>(i) * step_m;
    std::size_t end = i;
    while (end + 1 < points && (stiffness_of(end) >= stiff_threshold_N_per_m ||
                                (end + 2 < points && stiffness_of(end + 1) >= stiff_threshold_N_per_m))) {
      region.stiffness_N_per_m = std::max(region.stiffness_N_per_m, stiffness_of(end));
      ++end;
    }
    region.high_m = field.min_m + static_cast<double>(end) * step_m;
    region.low_is_edge = i > 0;
    region.high_is_edge = end + 1 < points;
    field.regions.push_back(region);
    i = end + 1;
  }
  return field;
}

}  // namespace

ForceField scan_force_field(const Scene& scene, double stiff_threshold_N_per_m) {
  require_sampleable_workspace(scene);
  ForceField field;
  field.min_m = scene.safety.workspace_min_m;
  field.step_m = kFieldStep_m;
  // Scripts too slow for the loop, in their first calls or in the scan: no field.
  if (std::optional<CheckResult> pace = check_script_pace(scene)) throw ScriptsTooSlow(std::move(*pace));
  return sample_field(scene, stiff_threshold_N_per_m, field);
}

ForceField probe_force_field(const Scene& scene, double stiff_threshold_N_per_m) {
  try {
    return scan_force_field(scene, stiff_threshold_N_per_m);
  } catch (const ScriptsTooSlow& slow) {
    ForceField field;
    field.min_m = scene.safety.workspace_min_m;
    field.step_m = kFieldStep_m;
    field.too_slow = slow.what();
    return field;
  }
}

}  // namespace hapscene
