#include "engine/harness/planar_route.hpp"

#include <algorithm>
#include <cmath>

#include "engine/harness/scenario_timing.hpp"

namespace hapscene {
namespace {

// The deepest any shape's solid comes along a segment (its points every 0.5 mm).
double deepest_along(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& a, const Vec2& b, int* which) {
  const int steps = std::max(1, static_cast<int>(std::ceil(norm(b - a) / 5e-4)));
  double deepest = -INFINITY;
  for (int i = 0; i <= steps; ++i) {
    const Vec2 p = a + (b - a) * (static_cast<double>(i) / steps);
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      const double d = shapes[k].depth_m(p);
      if (d > deepest) {
        deepest = d;
        *which = static_cast<int>(k);
      }
    }
  }
  return deepest;
}

// Waypoints from a to b that keep off every solid: a straight segment when it stays
// clear; else through its middle pushed out of the offending shape, recursively.
void route(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& a, const Vec2& b, int level,
           std::vector<Vec2>* out) {
  int which = -1;
  const double allowed = std::max(-0.5 * kRouteClearance_m,
                                  std::max(deepest_along(shapes, a, a, &which), deepest_along(shapes, b, b, &which)) + 1e-4);
  if (level >= 6 || deepest_along(shapes, a, b, &which) <= allowed || which < 0) {
    out->push_back(b);
    return;
  }
  const PlanarShapeGeometry& shape = shapes[static_cast<std::size_t>(which)];
  const Vec2 middle = (a + b) * 0.5;
  const Vec2 surface = shape.nearest_boundary_m(middle);
  const Vec2 across = unit_or(Vec2{{-(b - a)[1], (b - a)[0]}}, Vec2{{1.0, 0.0}});
  const Vec2 out_dir = shape.depth_m(middle) > 0.0 ? unit_or(surface - middle, across) : unit_or(middle - surface, across);
  const Vec2 via = surface + kRouteClearance_m * out_dir;
  route(shapes, a, via, level + 1, out);
  route(shapes, via, b, level + 1, out);
}

// Whether a routed leg keeps off every solid, by route's own measure.
bool leg_clear(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& a, const Vec2& b) {
  int which = -1;
  const double allowed = std::max(-0.5 * kRouteClearance_m,
                                  std::max(deepest_along(shapes, a, a, &which), deepest_along(shapes, b, b, &which)) + 1e-4);
  return deepest_along(shapes, a, b, &which) <= allowed;
}

}  // namespace

Vec2 unit_or(const Vec2& v, const Vec2& fallback) {
  const double length = norm(v);
  return length > 1e-12 ? v / length : fallback;
}

// The unit normal out of the solid at p (minus the gradient of the depth).
Vec2 outward_at(const PlanarShapeGeometry& shape, const Vec2& p_m) {
  constexpr double h = 1e-5;
  const Vec2 gradient{{(shape.depth_m(p_m + Vec2{{h, 0.0}}) - shape.depth_m(p_m - Vec2{{h, 0.0}})) / (2 * h),
                       (shape.depth_m(p_m + Vec2{{0.0, h}}) - shape.depth_m(p_m - Vec2{{0.0, h}})) / (2 * h)}};
  return unit_or(-gradient, Vec2{{1.0, 0.0}});
}

ReachableFree::ReachableFree(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& low, const Vec2& high,
                             const Vec2& start_m)
    : shapes_(shapes) {
  low_ = low + Vec2{{scenario_timing::kWorkspaceMargin_m, scenario_timing::kWorkspaceMargin_m}};
  const Vec2 size = high - low_ - Vec2{{scenario_timing::kWorkspaceMargin_m, scenario_timing::kWorkspaceMargin_m}};
  columns_ = std::max(1, static_cast<int>(std::floor(size[0] / kReachCell_m)) + 1);
  rows_ = std::max(1, static_cast<int>(std::floor(size[1] / kReachCell_m)) + 1);
  std::vector<char> free(static_cast<std::size_t>(columns_ * rows_), 0);
  int first = -1;
  double first_m = INFINITY;
  for (int cell = 0; cell < columns_ * rows_; ++cell) {
    const Vec2 c = centre(cell);
    double deepest = -INFINITY;
    for (const PlanarShapeGeometry& shape : shapes) deepest = std::max(deepest, shape.depth_m(c));
    free[static_cast<std::size_t>(cell)] = deepest <= -kReachClearance_m;
    if (free[static_cast<std::size_t>(cell)] && norm(c - start_m) < first_m) {
      first_m = norm(c - start_m);
      first = cell;
    }
  }
  // Breadth first from the start's cell; `from_` keeps each cell's way back.
  from_.assign(free.size(), -2);
  if (first < 0) return;
  std::vector<int> queue{first};
  from_[static_cast<std::size_t>(first)] = -1;
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const int cell = queue[next];
    const int column = cell % columns_;
    const int row = cell / columns_;
    const int neighbours[4][2] = {{column - 1, row}, {column + 1, row}, {column, row - 1}, {column, row + 1}};
    for (const auto& n : neighbours) {
      if (n[0] < 0 || n[0] >= columns_ || n[1] < 0 || n[1] >= rows_) continue;
      const int other = n[1] * columns_ + n[0];
      if (!free[static_cast<std::size_t>(other)] || from_[static_cast<std::size_t>(other)] != -2) continue;
      from_[static_cast<std::size_t>(other)] = cell;
      queue.push_back(other);
    }
  }
}

// A way from a to b (both reachable) through reachable cells, its corners cut where a
// straight leg stays half the route clearance off every solid.
std::vector<Vec2> ReachableFree::way(const Vec2& a, const Vec2& b) const {
  // Cells from b back to the start, and from a back to the start: joined where they meet.
  auto to_start = [&](int cell) {
    std::vector<int> cells;
    for (; cell >= 0; cell = from_[static_cast<std::size_t>(cell)]) cells.push_back(cell);
    return cells;
  };
  const std::vector<int> from_a = to_start(static_cast<int>(cell_at(a)));
  const std::vector<int> from_b = to_start(static_cast<int>(cell_at(b)));
  std::size_t shared = 0;  // cells the two ways share at their start ends
  while (shared < from_a.size() && shared < from_b.size() &&
         from_a[from_a.size() - 1 - shared] == from_b[from_b.size() - 1 - shared]) {
    ++shared;
  }
  std::vector<Vec2> points{a};
  for (std::size_t i = 0; i + shared < from_a.size(); ++i) points.push_back(centre(from_a[i]));
  points.push_back(centre(from_a[from_a.size() - shared]));
  for (std::size_t i = from_b.size() - shared; i-- > 0;) points.push_back(centre(from_b[i]));
  points.push_back(b);
  // Greedy line of sight: from each kept point, the farthest next point still in view.
  std::vector<Vec2> kept;
  std::size_t at = 0;
  while (at + 1 < points.size()) {
    std::size_t reach = at + 1;
    while (reach + 1 < points.size() && in_view(points[at], points[reach + 1])) ++reach;
    kept.push_back(points[reach]);
    at = reach;
  }
  return kept;
}

bool ReachableFree::in_view(const Vec2& a, const Vec2& b) const {
  int which = -1;
  return deepest_along(shapes_, a, b, &which) <= -0.5 * kRouteClearance_m;
}

std::vector<Vec2> way_round_solids(const std::vector<PlanarShapeGeometry>& shapes, const ReachableFree* free,
                                   const Vec2& from_m, const Vec2& to_m) {
  std::vector<Vec2> points;
  route(shapes, from_m, to_m, 0, &points);
  bool clear = true;
  Vec2 from = from_m;
  for (const Vec2& p : points) {
    clear = clear && leg_clear(shapes, from, p);
    from = p;
  }
  if (!clear && free != nullptr && free->reachable(from_m) && free->reachable(to_m)) {
    points = free->way(from_m, to_m);
  }
  return points;
}

// p moved out of every solid it is in or within the route clearance of (to that far
// off the nearest boundary, on the free side).
Vec2 free_point(const std::vector<PlanarShapeGeometry>& shapes, Vec2 p) {
  for (int pass = 0; pass < 3; ++pass) {
    for (const PlanarShapeGeometry& shape : shapes) {
      const double depth = shape.depth_m(p);
      if (depth <= -kRouteClearance_m) continue;
      const Vec2 surface = shape.nearest_boundary_m(p);
      const Vec2 out = depth > 0.0 ? unit_or(surface - p, outward_at(shape, surface)) : unit_or(p - surface, outward_at(shape, surface));
      p = surface + kRouteClearance_m * out;
    }
  }
  return p;
}

// Whether p is at least clearance off every solid.
bool shapes_clear(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& p_m, double clearance_m) {
  for (const PlanarShapeGeometry& shape : shapes) {
    if (shape.depth_m(p_m) > -clearance_m + 1e-9) return false;
  }
  return true;
}

}  // namespace hapscene
