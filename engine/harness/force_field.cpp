#include "engine/harness/force_field.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/step.hpp"

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

ForceField probe_force_field(const Scene& scene, double stiff_threshold_N_per_m, double step_m) {
  ForceField field;
  field.min_m = scene.safety.workspace_min_m;
  field.step_m = step_m;
  const double span_m = scene.safety.workspace_max_m - field.min_m;
  const auto points = static_cast<std::size_t>(std::floor(span_m / step_m)) + 1;

  // Sample the field at rest, before and after the static safety rules.
  TickState state = make_tick_state(scene);
  SafetyCounters counters;
  for (std::size_t i = 0; i < points; ++i) {
    EffectInput input;
    input.x_m = field.min_m + static_cast<double>(i) * step_m;
    input.dt_s = scene.period_s;
    const double force_N = sum_effects_N(scene, input, state.scripts);
    field.force_N.push_back(std::isfinite(force_N) ? force_N : 0.0);
    field.output_N.push_back(apply_static_safety(scene.safety, input.x_m, force_N, &counters));
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

}  // namespace hapscene
