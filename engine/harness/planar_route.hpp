#pragma once
// Ways for validate's 2-D hand round a scene's solids (planar_validate_scenario.cpp's
// scenarios travel on them): a straight leg where it stays clear, else bent round the
// shape in the way (recursively), else through the free part of the workspace the hand
// can reach from the start (ReachableFree), a grid of 1 mm cells.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "engine/harness/planar_shape_list.hpp"

namespace hapscene {

inline constexpr double kRouteClearance_m = 0.003;   // the hand passes shapes this far off
inline constexpr double kReachCell_m = 0.001;        // the reachable free part's cells
inline constexpr double kReachClearance_m = 0.001;   // a free cell's centre is this far off every solid

// v at unit length, or `fallback` where v is (nearly) zero.
Vec2 unit_or(const Vec2& v, const Vec2& fallback);
// The unit normal out of the solid at p (minus the gradient of the depth).
Vec2 outward_at(const PlanarShapeGeometry& shape, const Vec2& p_m);

// The free part of the workspace the hand can reach from the start without crossing a
// solid: the workspace box (less the hand's margin) in cells kReachCell_m wide, a cell
// free when every solid is at least kReachClearance_m from its centre, flooded through
// free neighbours (4 of them) from the free cell nearest the start. A frame of walls round
// the start keeps the hand inside it; a room no free path enters is out of reach.
class ReachableFree {
 public:
  ReachableFree(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& low, const Vec2& high, const Vec2& start_m);

  // Whether p's cell is free and reachable.
  bool reachable(const Vec2& p_m) const { return from_.empty() ? false : from_[cell_at(p_m)] != -2 && cell_inside(p_m); }

  // A way from a to b (both reachable) through reachable cells, its corners cut where a
  // straight leg stays half the route clearance off every solid.
  std::vector<Vec2> way(const Vec2& a, const Vec2& b) const;

 private:
  Vec2 centre(int cell) const {
    return low_ + Vec2{{(cell % columns_) * kReachCell_m, (cell / columns_) * kReachCell_m}};
  }
  bool cell_inside(const Vec2& p_m) const {
    const Vec2 offset = (p_m - low_) / kReachCell_m;
    return offset[0] > -0.5 && offset[1] > -0.5 && offset[0] < columns_ - 0.5 && offset[1] < rows_ - 0.5;
  }
  std::size_t cell_at(const Vec2& p_m) const {
    const Vec2 offset = (p_m - low_) / kReachCell_m;
    const int column = std::clamp(static_cast<int>(std::lround(offset[0])), 0, columns_ - 1);
    const int row = std::clamp(static_cast<int>(std::lround(offset[1])), 0, rows_ - 1);
    return static_cast<std::size_t>(row * columns_ + column);
  }
  bool in_view(const Vec2& a, const Vec2& b) const;

  const std::vector<PlanarShapeGeometry>& shapes_;
  Vec2 low_{};
  int columns_{};
  int rows_{};
  std::vector<int> from_;  // per cell: the cell it was reached from, -1 the start, -2 not reached
};

// The waypoints from `from_m` to `to_m` round the solids: the bent legs when each keeps
// off them, else (a leg bent into a solid: walls round the way, a wall against another)
// the way through the reachable free cells, when `free` has both ends.
std::vector<Vec2> way_round_solids(const std::vector<PlanarShapeGeometry>& shapes, const ReachableFree* free,
                                   const Vec2& from_m, const Vec2& to_m);

// p moved out of every solid it is in or within the route clearance of (to that far off
// the nearest boundary, on the free side).
Vec2 free_point(const std::vector<PlanarShapeGeometry>& shapes, Vec2 p);

// Whether p is at least clearance off every solid.
bool shapes_clear(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& p_m, double clearance_m);

}  // namespace hapscene
