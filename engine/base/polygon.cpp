#include "engine/base/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace hapscene {
namespace {

// Cells per axis at most: bounds the grid's memory whatever the outline's proportions.
constexpr int kMaxCellsPerAxis = 512;

}  // namespace

PolygonGrid polygon_grid_shape(const std::vector<Vec2>& points) {
  Vec2 low = points.front();
  Vec2 high = points.front();
  for (const Vec2& p : points) {
    for (int k = 0; k < 2; ++k) {
      low[k] = std::min(low[k], p[k]);
      high[k] = std::max(high[k], p[k]);
    }
  }
  const double width_m = high[0] - low[0];
  const double height_m = high[1] - low[1];
  const double cells = static_cast<double>(points.size());
  const auto clamp_cells = [](double count) {
    return static_cast<int>(std::clamp(std::round(count), 1.0, static_cast<double>(kMaxCellsPerAxis)));
  };
  PolygonGrid shape;
  shape.origin_m = low;
  shape.columns = clamp_cells(std::sqrt(cells * width_m / height_m));
  shape.rows = clamp_cells(std::sqrt(cells * height_m / width_m));
  shape.cell_width_m = width_m / shape.columns;
  shape.cell_height_m = height_m / shape.rows;
  return shape;
}

namespace {

// Whether segment a-b passes through the rectangle [low, high] (boundary included).
bool segment_touches_box(const Vec2& a, const Vec2& b, const Vec2& low, const Vec2& high) noexcept {
  if (std::max(a[0], b[0]) < low[0] || std::min(a[0], b[0]) > high[0]) return false;
  if (std::max(a[1], b[1]) < low[1] || std::min(a[1], b[1]) > high[1]) return false;
  // The corners all strictly on one side of the segment's line: it misses the box.
  const Vec2 d = b - a;
  int above = 0;
  int below = 0;
  const Vec2 corners[4] = {low, Vec2{{high[0], low[1]}}, high, Vec2{{low[0], high[1]}}};
  for (const Vec2& corner : corners) {
    const double c = cross(d, corner - a);
    above += c > 0.0;
    below += c < 0.0;
  }
  return above != 4 && below != 4;
}

// The cell range [first, last] along one axis that [low, high] overlaps, or false when
// it lies outside the grid.
bool cell_span(double low, double high, double origin, double cell, int count, double margin,
               int* first, int* last) noexcept {
  const double extent = cell * count;
  if (high < origin - margin || low > origin + extent + margin) return false;
  const auto index = [&](double value) {
    return static_cast<int>(std::clamp(std::floor((value - origin) / cell), 0.0, count - 1.0));
  };
  *first = index(low - margin);
  *last = index(high + margin);
  return true;
}

// Visits every cell of the grid that segment a-b passes through (cells grown by margin).
template <typename Visit>
void for_each_cell(const PolygonGrid& grid, const Vec2& a, const Vec2& b, Visit&& visit) noexcept {
  const double margin = kPolygonCellMargin * std::max(grid.cell_width_m, grid.cell_height_m);
  int c0 = 0, c1 = 0, r0 = 0, r1 = 0;
  if (!cell_span(std::min(a[0], b[0]), std::max(a[0], b[0]), grid.origin_m[0], grid.cell_width_m,
                 grid.columns, margin, &c0, &c1)) {
    return;
  }
  if (!cell_span(std::min(a[1], b[1]), std::max(a[1], b[1]), grid.origin_m[1], grid.cell_height_m,
                 grid.rows, margin, &r0, &r1)) {
    return;
  }
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const Vec2 low{{grid.origin_m[0] + c * grid.cell_width_m - margin,
                      grid.origin_m[1] + r * grid.cell_height_m - margin}};
      const Vec2 high{{grid.origin_m[0] + (c + 1) * grid.cell_width_m + margin,
                       grid.origin_m[1] + (r + 1) * grid.cell_height_m + margin}};
      if (c0 == c1 && r0 == r1) {
        visit(r * grid.columns + c);  // the segment's box lies in this one cell
      } else if (segment_touches_box(a, b, low, high)) {
        visit(r * grid.columns + c);
      }
    }
  }
}

}  // namespace

void build_polygon_grid(const std::vector<Vec2>& points, const PolygonGrid& grid, std::vector<int>* cell_start,
                        std::vector<int>* cell_edges) {
  const int n = static_cast<int>(points.size());
  const std::size_t cells = static_cast<std::size_t>(grid.columns) * static_cast<std::size_t>(grid.rows);
  std::vector<int> counts(cells, 0);
  for (int i = 0; i < n; ++i) {
    for_each_cell(grid, points[static_cast<std::size_t>(i)], points[static_cast<std::size_t>((i + 1) % n)],
                  [&](int cell) { ++counts[static_cast<std::size_t>(cell)]; });
  }
  cell_start->assign(cells + 1, 0);
  for (std::size_t k = 0; k < cells; ++k) (*cell_start)[k + 1] = (*cell_start)[k] + counts[k];
  cell_edges->assign(static_cast<std::size_t>(cell_start->back()), 0);
  std::vector<int> filled(cell_start->begin(), cell_start->end() - 1);
  for (int i = 0; i < n; ++i) {
    for_each_cell(grid, points[static_cast<std::size_t>(i)], points[static_cast<std::size_t>((i + 1) % n)],
                  [&](int cell) { (*cell_edges)[static_cast<std::size_t>(filled[static_cast<std::size_t>(cell)]++)] = i; });
  }
}

namespace {

int sign_of(double value) noexcept { return (value > 0.0) - (value < 0.0); }

// Whether point c on the line of a-b lies within the segment's bounding box.
bool within_box(const Vec2& a, const Vec2& b, const Vec2& c) noexcept {
  return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= c[1] &&
         c[1] <= std::max(a[1], b[1]);
}

}  // namespace

bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) noexcept {
  const int o1 = sign_of(cross(b - a, c - a));
  const int o2 = sign_of(cross(b - a, d - a));
  const int o3 = sign_of(cross(d - c, a - c));
  const int o4 = sign_of(cross(d - c, b - c));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && within_box(a, b, c)) || (o2 == 0 && within_box(a, b, d)) ||
         (o3 == 0 && within_box(c, d, a)) || (o4 == 0 && within_box(c, d, b));
}

double polygon_signed_area_m2(const std::vector<Vec2>& points) {
  double twice = 0.0;
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) twice += cross(points[i], points[(i + 1) % n]);
  return 0.5 * twice;
}

std::string simple_polygon_problem(const std::vector<Vec2>& points) {
  const std::size_t n = points.size();
  if (n < 3) return "a polygon needs at least 3 points, got " + std::to_string(n);
  const auto name = [](std::size_t i) { return std::to_string(i); };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (points[i] == points[j]) {
      if (j == 0) {
        return "points " + name(n - 1) + " and 0 coincide: the outline closes by itself, leave out the last point";
      }
      return "points " + name(i) + " and " + name(j) + " coincide";
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 d1 = points[(i + 1) % n] - points[i];
    const Vec2 d2 = points[(i + 2) % n] - points[(i + 1) % n];
    if (cross(d1, d2) == 0.0 && dot(d1, d2) < 0.0) {
      return "edges " + name(i) + " and " + name((i + 1) % n) + " fold back on each other at point " +
             name((i + 1) % n);
    }
  }
  const PolygonGrid extent = [&] {
    Vec2 low = points.front(), high = points.front();
    for (const Vec2& p : points) {
      for (int k = 0; k < 2; ++k) low[k] = std::min(low[k], p[k]), high[k] = std::max(high[k], p[k]);
    }
    PolygonGrid shape;
    shape.cell_width_m = high[0] - low[0];
    shape.cell_height_m = high[1] - low[1];
    return shape;
  }();
  if (!(extent.cell_width_m > 0.0) || !(extent.cell_height_m > 0.0)) {
    return "the points lie on one line: the polygon encloses no area";
  }
  // Edges that share a point can only do so in a cell they both pass through.
  const PolygonGrid grid = polygon_grid_shape(points);
  std::vector<int> cell_start, cell_edges;
  build_polygon_grid(points, grid, &cell_start, &cell_edges);
  for (std::size_t k = 0; k + 1 < cell_start.size(); ++k) {
    for (int a = cell_start[k]; a < cell_start[k + 1]; ++a) {
      for (int b = a + 1; b < cell_start[k + 1]; ++b) {
        std::size_t i = static_cast<std::size_t>(cell_edges[static_cast<std::size_t>(a)]);
        std::size_t j = static_cast<std::size_t>(cell_edges[static_cast<std::size_t>(b)]);
        if (i == j) continue;
        if (i > j) std::swap(i, j);
        if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours share their vertex
        if (segments_meet(points[i], points[(i + 1) % n], points[j], points[(j + 1) % n])) {
          return "edges " + name(i) + " (points " + name(i) + " to " + name((i + 1) % n) + ") and " + name(j) +
                 " (points " + name(j) + " to " + name((j + 1) % n) +
                 ") cross or touch: the outline must not intersect itself";
        }
      }
    }
  }
  if (polygon_signed_area_m2(points) == 0.0) return "the polygon encloses no area";
  return {};
}

bool segment_meets_box(const Vec2& a, const Vec2& b, const Vec2& low, const Vec2& high, BoxSides sides) noexcept {
  const bool closed = sides == BoxSides::closed;
  double enter = 0.0;  // the part of the segment within the box so far: [enter, leave]
  double leave = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    const double d = b[axis] - a[axis];
    if (d == 0.0) {  // parallel to this axis's sides: inside their band or never
      const bool within = closed ? a[axis] >= low[axis] && a[axis] <= high[axis]
                                 : a[axis] > low[axis] && a[axis] < high[axis];
      if (!within) return false;
      continue;
    }
    double t0 = (low[axis] - a[axis]) / d;
    double t1 = (high[axis] - a[axis]) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    if (closed ? enter > leave : enter >= leave) return false;
  }
  return true;
}

}  // namespace hapscene
