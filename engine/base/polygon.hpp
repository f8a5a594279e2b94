#pragma once
// Polygons in the plane, as read from files: the check every polygon must pass before
// anything uses it (a 2-D shape's outline, a device's workspace), and the uniform grid of
// its edges that the check and the shapes' god-object proxy both search
// (engine/effects/planar/polygon_outline.hpp).
#include <string>
#include <vector>

#include "engine/base/axes.hpp"

namespace hapscene {

// Edges are listed in every cell they come within this fraction of a cell of, so a
// crossing near a cell's border is found from either cell.
inline constexpr double kPolygonCellMargin = 1e-9;

// A uniform grid over a polygon's bounding box: cell (c, r) covers
// [origin + c w, origin + (c + 1) w) x [origin + r h, origin + (r + 1) h).
struct PolygonGrid {
  Vec2 origin_m{};
  double cell_width_m{1.0};
  double cell_height_m{1.0};
  int columns{1};
  int rows{1};
};

// About one cell per edge, the cells about square, over the points' bounding box (at
// most 512 cells per axis, whatever the proportions).
PolygonGrid polygon_grid_shape(const std::vector<Vec2>& points);

// Edge i (point i to point i + 1, the last back to 0) listed in every cell it passes
// through: the edges of cell k are cell_edges[cell_start[k] .. cell_start[k + 1]).
void build_polygon_grid(const std::vector<Vec2>& points, const PolygonGrid& grid, std::vector<int>* cell_start,
                        std::vector<int>* cell_edges);

// Half the sum of cross(point i, point i + 1): positive when the points run anticlockwise.
double polygon_signed_area_m2(const std::vector<Vec2>& points);

// Empty when `points` make a simple polygon with an area; else what is wrong, naming the
// points and edges: fewer than 3 points, coinciding neighbours, edges that fold back on
// each other, edges that cross or touch ("edges 0 (points 0 to 1) and 2 (points 2 to 3)
// cross or touch: ..."), all points on one line, no area. The caller prefixes the place.
std::string simple_polygon_problem(const std::vector<Vec2>& points);

// Whether the closed segments a-b and c-d share a point (crossing, touching, overlapping).
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) noexcept;

// Whether segment a-b has a point in the box [low, high] (Liang-Barsky clipping): with its
// sides (closed), or strictly inside them (open: a segment along a side, or through a
// corner only, does not count).
enum class BoxSides { closed, open };
bool segment_meets_box(const Vec2& a, const Vec2& b, const Vec2& low, const Vec2& high, BoxSides sides) noexcept;

}  // namespace hapscene
