#include "engine/effects/planar/polygon_outline.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/polygon.hpp"

namespace hapscene {
namespace {

// Work per tick at most: steps (a straight move, a slide along an edge or a decision on
// a vertex) and straight moves (each a query of the grid along the path). A proxy left
// far behind the handle (which went through the solid) catches up over the next ticks;
// it is on the outline or in free space after every step, so stopping early is safe.
constexpr int kMaxStepsPerTick = 64;
constexpr int kMaxStraightMovesPerTick = 8;

// Visits the cells segment a-b passes through in order from a (a grid walk), calling
// visit(cell, t_leave) with the fraction of the path at which it leaves the cell; stops
// when visit returns true. Edges are listed in every cell they come within a margin of,
// so a crossing near a cell's border is found in either cell.
template <typename Visit>
void walk_cells(const PolygonGrid& grid, const Vec2& a, const Vec2& b, Visit&& visit) noexcept {
  const Vec2 d = b - a;
  const double cell[2] = {grid.cell_width_m, grid.cell_height_m};
  const int count[2] = {grid.columns, grid.rows};
  const double margin = kPolygonCellMargin * std::max(grid.cell_width_m, grid.cell_height_m);
  // Clip the path to the grid's box (grown by the margin, as the cells' lists are).
  double t_in = 0.0;
  double t_out = 1.0;
  for (int k = 0; k < 2; ++k) {
    const double low = grid.origin_m[k] - margin;
    const double high = grid.origin_m[k] + cell[k] * count[k] + margin;
    if (d[k] == 0.0) {
      if (a[k] < low || a[k] > high) return;
      continue;
    }
    double t_low = (low - a[k]) / d[k];
    double t_high = (high - a[k]) / d[k];
    if (t_low > t_high) std::swap(t_low, t_high);
    t_in = std::max(t_in, t_low);
    t_out = std::min(t_out, t_high);
  }
  if (t_in > t_out) return;
  int index[2];
  int step[2];
  double t_next[2];   // where the path crosses into the next cell along each axis
  double t_delta[2];  // path fraction per cell along each axis
  const Vec2 start = a + d * t_in;
  for (int k = 0; k < 2; ++k) {
    index[k] = static_cast<int>(std::clamp(std::floor((start[k] - grid.origin_m[k]) / cell[k]), 0.0, count[k] - 1.0));
    if (d[k] > 0.0) {
      step[k] = 1;
      t_next[k] = (grid.origin_m[k] + (index[k] + 1) * cell[k] - a[k]) / d[k];
      t_delta[k] = cell[k] / d[k];
    } else if (d[k] < 0.0) {
      step[k] = -1;
      t_next[k] = (grid.origin_m[k] + index[k] * cell[k] - a[k]) / d[k];
      t_delta[k] = -cell[k] / d[k];
    } else {
      step[k] = 0;
      t_next[k] = INFINITY;
      t_delta[k] = INFINITY;
    }
  }
  // At most one cell per column and row crossed, plus the first.
  for (int guard = count[0] + count[1] + 2; guard > 0; --guard) {
    const int axis = t_next[0] < t_next[1] ? 0 : 1;
    const double t_leave = std::min(t_next[axis], t_out);
    if (visit(index[1] * grid.columns + index[0], t_leave)) return;
    if (t_next[axis] >= t_out) return;
    index[axis] += step[axis];
    if (index[axis] < 0 || index[axis] >= count[axis]) return;
    t_next[axis] += t_delta[axis];
  }
}

}  // namespace

PolygonOutline::PolygonOutline(const std::vector<Vec2>& points, bool solid_inside)
    : vertices_(points), solid_inside_(solid_inside) {
  const std::size_t n = points.size();
  // Free space is on the left of each edge (walking the points in order) when the points
  // run anticlockwise around a cage, or clockwise around a solid.
  const bool free_on_left = (polygon_signed_area_m2(points) > 0.0) != solid_inside;
  tangents_.resize(n);
  normals_.resize(n);
  lengths_m_.resize(n);
  wide_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // (simple_polygon_problem refused coinciding neighbours, so every edge has a
    // direction; its length and direction are taken without underflow, however short.)
    const Vec2 d = points[(i + 1) % n] - points[i];
    lengths_m_[i] = stable_norm(d);
    unit_vector(d, &tangents_[i]);
    const Vec2 left{{-tangents_[i][1], tangents_[i][0]}};
    normals_[i] = free_on_left ? left : -left;
  }
  // Vertex i joins edge i - 1 to edge i: a turn toward the free side narrows it.
  for (std::size_t i = 0; i < n; ++i) {
    const double turn = cross(tangents_[(i + n - 1) % n], tangents_[i]);
    wide_[i] = free_on_left ? turn <= 0.0 : turn >= 0.0;
  }
  const PolygonGrid grid = polygon_grid_shape(points);
  origin_m_ = grid.origin_m;
  cell_width_m_ = grid.cell_width_m;
  cell_height_m_ = grid.cell_height_m;
  columns_ = grid.columns;
  rows_ = grid.rows;
  build_polygon_grid(points, grid, &cell_start_, &cell_edges_);
  // The grid spans the vertices' bounding box; its margin is a billionth of a cell and an
  // edge's snap a billionth of its length (at most the box's diagonal), so 4 billionths
  // of the larger side covers both.
  const Vec2 high{{grid.origin_m[0] + grid.cell_width_m * grid.columns, grid.origin_m[1] + grid.cell_height_m * grid.rows}};
  const double reach_m = 4e-9 * std::max(high[0] - grid.origin_m[0], high[1] - grid.origin_m[1]);
  for (int k = 0; k < 2; ++k) {
    double low = grid.origin_m[k];
    double top = high[k];
    for (const Vec2& p : points) {
      low = std::min(low, p[k]);
      top = std::max(top, p[k]);
    }
    reach_low_m_[k] = low - reach_m;
    reach_high_m_[k] = top + reach_m;
  }
}

int PolygonOutline::most_edges_per_cell() const noexcept {
  int most = 0;
  for (std::size_t k = 0; k + 1 < cell_start_.size(); ++k) most = std::max(most, cell_start_[k + 1] - cell_start_[k]);
  return most;
}

template <typename Visit, typename Done>
void PolygonOutline::for_each_edge_near(const Vec2& a, const Vec2& b, Visit&& visit, Done&& done) const noexcept {
  const PolygonGrid grid{origin_m_, cell_width_m_, cell_height_m_, columns_, rows_};
  walk_cells(grid, a, b, [&](int cell, double t_leave) {
    const int end = cell_start_[static_cast<std::size_t>(cell) + 1];
    for (int k = cell_start_[static_cast<std::size_t>(cell)]; k < end; ++k) {
      visit(cell_edges_[static_cast<std::size_t>(k)]);
    }
    return done(t_leave);
  });
}

PolygonOutline::Hit PolygonOutline::first_entry(const Vec2& a, const Vec2& b, int skip_a,
                                                int skip_b) const noexcept {
  Hit best;
  best.t = 2.0;
  for_each_edge_near(a, b, [&](int e) {
    if (e == skip_a || e == skip_b) return;
    const double side_a = side(e, a);
    const double side_b = side(e, b);
    if (!(side_a >= 0.0 && side_b < 0.0)) return;  // not entering the solid through this line
    const double t = side_a / (side_a - side_b);
    if (!(t < best.t)) return;
    const double along_m = along(e, a + (b - a) * t);
    const double snap_m = kVertexSnap * length_m(e);
    if (along_m < -snap_m || along_m > length_m(e) + snap_m) return;  // the line, not the edge
    best = Hit{e, t, along_m};
  }, [&](double t_leave) { return best.t <= t_leave; });  // later cells only hold later crossings
  return best;
}

void PolygonOutline::place(const Hit& hit, Vec2* proxy, ProxyContact* contact, int* feature) const noexcept {
  const double snap_m = kVertexSnap * length_m(hit.edge);
  if (hit.along_m <= snap_m) {
    *proxy = vertex(hit.edge);
    *contact = ProxyContact::vertex;
    *feature = hit.edge;
  } else if (hit.along_m >= length_m(hit.edge) - snap_m) {
    *proxy = vertex(next(hit.edge));
    *contact = ProxyContact::vertex;
    *feature = next(hit.edge);
  } else {
    *proxy = vertex(hit.edge) + tangent(hit.edge) * hit.along_m;
    *contact = ProxyContact::edge;
    *feature = hit.edge;
  }
}

void PolygonOutline::step_proxy_full(const Vec2& x_m, const FrictionCoefficients& friction,
                                     PlanarProxyState& state) const noexcept {
  if (!all_finite(x_m) || vertices_.empty()) return;
  if (!state.started) {
    state = PlanarProxyState{};
    state.proxy_m = x_m;
    state.started = true;
    return;
  }
  Vec2 proxy = state.proxy_m;
  ProxyContact contact = state.contact;
  int feature = state.feature;
  bool sliding = state.sliding;
  int reference = contact == ProxyContact::edge ? feature : state.reference_edge;
  int straight_moves = 0;
  // Straight toward x from where the proxy is; true when it got there.
  const auto move_toward_x = [&](int skip_a, int skip_b) {
    ++straight_moves;
    const Hit hit = first_entry(proxy, x_m, skip_a, skip_b);
    sliding = false;
    if (hit.edge < 0) {
      proxy = x_m;
      contact = ProxyContact::none;
      feature = -1;
      return true;
    }
    place(hit, &proxy, &contact, &feature);
    reference = hit.edge;
    return false;
  };
  // Whether a slide over vertex v onto edge e keeps the proxy within a quarter turn of the
  // reference: over a wide vertex (round a convex part of the solid) e's normal must be
  // turned less than a quarter turn from the reference's (their dot product positive), so a
  // slide never carries the proxy round to the far side, however deep the handle went
  // (through the solid within one tick): it holds on the vertex instead. (A narrow vertex,
  // a concave corner, turns the proxy toward the free side: no limit.)
  const auto within_quarter_turn = [&](int v, int e) {
    return !wide(v) || reference < 0 || dot(normal(e), normal(reference)) > 0.0;
  };
  int from_vertex = -1;  // the vertex a slide along the current edge started from
  for (int step = 0; step < kMaxStepsPerTick && straight_moves < kMaxStraightMovesPerTick; ++step) {
    if (contact == ProxyContact::none) {
      if (move_toward_x(-1, -1)) break;
      from_vertex = -1;
      continue;
    }
    if (contact == ProxyContact::edge) {
      const int e = feature;
      const double side_x = side(e, x_m);
      if (side_x > 0.0) {  // x is on the free side: leave the edge
        if (move_toward_x(e, e)) break;
        from_vertex = -1;
        continue;
      }
      // Slide toward the foot of the perpendicular from x, held back by friction.
      const double depth_m = -side_x;
      const double at_m = along(e, proxy);
      const double foot_m = along(e, x_m);
      double to_m = foot_m;
      bool stuck = false;
      if (friction.any()) {
        const double gap_m = foot_m - at_m;
        const double mu = sliding ? friction.dynamic_mu : friction.static_mu;
        if (std::fabs(gap_m) <= mu * depth_m) {
          stuck = true;
          sliding = false;
          to_m = at_m;
        } else {
          sliding = true;
          to_m = foot_m - std::copysign(friction.dynamic_mu * depth_m, gap_m);
        }
      }
      const double snap_m = kVertexSnap * length_m(e);
      int reached = -1;
      if (to_m <= snap_m) reached = e;
      if (to_m >= length_m(e) - snap_m) reached = next(e);
      if (reached < 0) {
        if (!stuck) proxy = vertex(e) + tangent(e) * to_m;
        break;
      }
      proxy = vertex(reached);
      contact = ProxyContact::vertex;
      feature = reached;
      if (stuck || reached == from_vertex) break;  // no further this tick
      continue;
    }
    // On a vertex: leave toward x, slide onto an edge, or hold.
    const int v = feature;
    const int in = previous(v);
    const int out = v;
    const double side_in = side(in, x_m);
    const double side_out = side(out, x_m);
    const bool x_free_here = wide(v) ? (side_in > 0.0 || side_out > 0.0) : (side_in >= 0.0 && side_out >= 0.0);
    if (x_free_here) {
      if (move_toward_x(in, out)) break;
      from_vertex = -1;
      continue;
    }
    const Vec2 d = x_m - proxy;
    const double gain_out = side_out <= 0.0 && within_quarter_turn(v, out) ? dot(d, tangent(out)) : 0.0;
    const double gain_in = side_in <= 0.0 && within_quarter_turn(v, in) ? -dot(d, tangent(in)) : 0.0;
    if (gain_out > kVertexSnap * length_m(out) && gain_out >= gain_in) {
      contact = ProxyContact::edge;
      feature = out;
    } else if (gain_in > kVertexSnap * length_m(in)) {
      contact = ProxyContact::edge;
      feature = in;
    } else {
      break;  // held in the corner
    }
    from_vertex = v;
  }
  // Stopped by the cap just after choosing an edge at a vertex: the proxy is still on
  // the vertex, and rests there (so a later move away skips both of its edges).
  if (contact == ProxyContact::edge) {
    const double at_m = along(feature, proxy);
    const double snap_m = kVertexSnap * length_m(feature);
    if (at_m <= snap_m || at_m >= length_m(feature) - snap_m) {
      feature = at_m <= snap_m ? feature : next(feature);
      proxy = vertex(feature);
      contact = ProxyContact::vertex;
    }
  }
  state.proxy_m = proxy;
  state.contact = contact;
  state.feature = feature;
  state.sliding = sliding;
  state.reference_edge = contact == ProxyContact::edge ? feature : contact == ProxyContact::vertex ? reference : -1;
}

bool PolygonOutline::in_solid(const Vec2& x_m) const noexcept {
  bool inside = false;
  const int n = edge_count();
  for (int i = 0; i < n; ++i) {
    const Vec2& a = vertex(i);
    const Vec2& b = vertex(next(i));
    if ((a[1] > x_m[1]) != (b[1] > x_m[1])) {
      const double crossing_x = a[0] + (x_m[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (x_m[0] < crossing_x) inside = !inside;
    }
  }
  return inside == solid_inside_;
}

Vec2 PolygonOutline::nearest_point(const Vec2& x_m) const noexcept {
  Vec2 best = x_m;
  double best_m2 = INFINITY;
  const int n = edge_count();
  for (int i = 0; i < n; ++i) {
    const double at_m = std::clamp(along(i, x_m), 0.0, length_m(i));
    const Vec2 point = at_m <= 0.0 ? vertex(i) : at_m >= length_m(i) ? vertex(next(i)) : vertex(i) + tangent(i) * at_m;
    const Vec2 gap = point - x_m;
    const double distance_m2 = dot(gap, gap);
    if (distance_m2 < best_m2) {
      best_m2 = distance_m2;
      best = point;
    }
  }
  return best;
}

Vec2 PolygonOutline::open_loop_proxy(const Vec2& x_m) const noexcept {
  return in_solid(x_m) ? nearest_point(x_m) : x_m;
}

}  // namespace hapscene
