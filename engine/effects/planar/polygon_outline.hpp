#pragma once
// A closed polygonal outline (a polygon's points, or a box's four corners) with the side
// its solid lies on, and the god-object proxy that renders it.
//
// Geometry. Edge i runs from vertex i to vertex i + 1 (the last back to 0). Each edge has
// a unit tangent and a unit normal pointing into free space, so the side of a point x is
// side(i, x) = (x - vertex i) . normal i: >= 0 on the free side, < 0 on the solid side
// of the edge's line. Every decision below reads sides through this one expression, so a
// point judged free once is judged free again. A vertex is "wide" when the free space
// around it spans more than half a turn (a convex corner of the solid) and "narrow" when
// less (a concave corner: the proxy can be held in it).
//
// Spatial index. A uniform grid over the outline's bounding box, about one cell per edge,
// lists the edges passing through each cell (built at load, fixed memory). A straight
// move of the proxy walks the cells its path passes through, in order, testing their
// edges, and stops at the first cell that holds a crossing.
//
// Closed loop (step_proxy). Each tick the proxy moves toward the handle x:
// - free: straight toward x; the first edge the path enters (from its free side to its
//   solid side) stops it there (on that edge, or on a vertex when within a billionth of
//   the edge's length of one);
// - on an edge: while x is on the edge's solid side the proxy slides along the edge to
//   the foot of the perpendicular from x (with friction: it sticks while that foot is
//   within mu_s times x's depth of it, else it slides to mu_d times the depth behind the
//   foot, and keeps the dynamic cone until it sticks again); at the edge's end it goes
//   on as on that vertex. When x is on the edge's free side the proxy leaves the edge
//   straight toward x (and may hit another edge);
// - on a vertex: it leaves toward x when x lies in the free space around the vertex;
//   else it slides onto whichever of the two edges brings it closer to x (the one with the
//   larger positive component of x - vertex along it); when neither does it holds there
//   (a concave corner holds). Over a wide vertex it never slides onto an edge whose
//   normal is turned a quarter turn or more from its reference edge's (the edge it
//   rested on at the start of the tick, or last met on a straight move): a handle that
//   went deep into a convex solid, past its middle, would otherwise draw the proxy round
//   to the far side, whose edges push the handle on through; it holds on the vertex.
// Each step brings the proxy closer to x. A tick takes at most 64 steps and 8 straight
// moves (bounded work whatever the outline); a proxy left far behind, when the handle
// went deep through the solid, catches up over the next ticks, always outside the solid
// (over thin teeth, by straight moves through the free space between them).
// The proxy never crosses an edge, so a thin polygon never pops through: the proxy stays
// on the side the handle came from until the handle leaves the solid there or slides off
// the end of the wall. A run that starts with the handle in the solid puts the proxy at
// the handle; the proxy then follows the handle through the solid (paths that leave the
// solid are not stopped, as in CHAI3D), so there is no force until the handle has left it.
//
// Open loop (no history): the proxy is the nearest point of the outline to x when x is in
// the solid (ties: the lowest edge index), else x. These scan every edge: they are for
// probes and field scans, not the tick.
#include <cmath>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/effects/planar/proxy_state.hpp"

namespace hapscene {

class PolygonOutline {
 public:
  // A hit or a slide within this fraction of an edge's length of one of its ends lands on
  // the vertex there (a nanometre on a metre-long edge: far below any sensor's resolution).
  static constexpr double kVertexSnap = 1e-9;

  PolygonOutline() = default;
  // Builds from points that pass simple_polygon_problem() (engine/base/polygon.hpp).
  // `solid_inside`: the enclosed area is solid (else everything outside it is, and it is
  // a cage).
  PolygonOutline(const std::vector<Vec2>& points, bool solid_inside);

  int edge_count() const noexcept { return static_cast<int>(vertices_.size()); }
  const Vec2& vertex(int i) const noexcept { return vertices_[static_cast<std::size_t>(i)]; }
  const Vec2& normal(int i) const noexcept { return normals_[static_cast<std::size_t>(i)]; }
  const Vec2& tangent(int i) const noexcept { return tangents_[static_cast<std::size_t>(i)]; }
  double length_m(int i) const noexcept { return lengths_m_[static_cast<std::size_t>(i)]; }
  bool wide(int vertex_index) const noexcept { return wide_[static_cast<std::size_t>(vertex_index)] != 0; }
  bool solid_inside() const noexcept { return solid_inside_; }
  // Grid size, for tests and reports.
  int grid_columns() const noexcept { return columns_; }
  int grid_rows() const noexcept { return rows_; }
  // Most edges listed in one cell.
  int most_edges_per_cell() const noexcept;

  // (x - vertex i) . normal i: >= 0 on the free side of edge i's line.
  double side(int i, const Vec2& x_m) const noexcept { return dot(x_m - vertex(i), normal(i)); }

  // Closed loop: moves the proxy in `state` toward x_m as described above. Non-finite
  // x_m leaves the state as it was.
  // A free proxy whose straight path to x_m passes clear of the outline's bounding box
  // (grown by more than any crossing's tolerance) cannot meet an edge: it goes to x_m
  // at once, as the full step would put it, without a call (the common case away from
  // a shape).
  // Likewise a frictionless proxy on an edge whose handle is still on the edge's solid
  // side, with the foot of the perpendicular well inside the edge: it slides to that foot
  // (the full step's first step, which ends there), in a few instructions.
  [[gnu::always_inline]] void step_proxy(const Vec2& x_m, const FrictionCoefficients& friction,
                                         PlanarProxyState& state) const noexcept {
    if (state.started && all_finite(x_m)) {
      if (state.contact == ProxyContact::none && clear_of_outline(state.proxy_m, x_m)) {
        state.proxy_m = x_m;
        state.feature = -1;
        state.sliding = false;
        return;
      }
      if (state.contact == ProxyContact::edge && !friction.any() && slide_on_edge(x_m, state)) return;
    }
    step_proxy_full(x_m, friction, state);
  }

  // Open loop: whether x_m is in the solid (crossing number; on the outline counts as
  // either), the nearest point of the outline, and the proxy (nearest point when in the
  // solid, else x_m).
  bool in_solid(const Vec2& x_m) const noexcept;
  Vec2 nearest_point(const Vec2& x_m) const noexcept;
  Vec2 open_loop_proxy(const Vec2& x_m) const noexcept;

 private:
  struct Hit {
    int edge{-1};
    double t{};          // fraction of the path at the crossing
    double along_m{};    // distance along the edge from its start
  };
  // Whether segment a-b lies wholly outside the grown bounding box (false for NaN).
  bool clear_of_outline(const Vec2& a, const Vec2& b) const noexcept {
    return (a[0] < reach_low_m_[0] && b[0] < reach_low_m_[0]) || (a[0] > reach_high_m_[0] && b[0] > reach_high_m_[0]) ||
           (a[1] < reach_low_m_[1] && b[1] < reach_low_m_[1]) || (a[1] > reach_high_m_[1] && b[1] > reach_high_m_[1]);
  }
  void step_proxy_full(const Vec2& x_m, const FrictionCoefficients& friction,
                       PlanarProxyState& state) const noexcept;
  // The frictionless slide along the proxy's edge when it ends inside the edge, as the full
  // step decides it (its end and the proxy placed there both farther than the vertex snap
  // from either vertex); false, and the state untouched, otherwise.
  [[gnu::always_inline]] bool slide_on_edge(const Vec2& x_m, PlanarProxyState& state) const noexcept {
    const int e = state.feature;
    if (!(side(e, x_m) <= 0.0)) return false;  // x left the solid side: the proxy leaves the edge
    const double length = length_m(e);
    const double snap_m = kVertexSnap * length;
    const double foot_m = along(e, x_m);
    if (!(foot_m > snap_m && foot_m < length - snap_m)) return false;
    const Vec2 proxy = vertex(e) + tangent(e) * foot_m;
    const double at_m = along(e, proxy);
    if (!(at_m > snap_m && at_m < length - snap_m)) return false;
    state.proxy_m = proxy;
    return true;
  }
  int next(int i) const noexcept { return i + 1 == edge_count() ? 0 : i + 1; }
  int previous(int i) const noexcept { return i == 0 ? edge_count() - 1 : i - 1; }
  double along(int i, const Vec2& x_m) const noexcept { return dot(x_m - vertex(i), tangent(i)); }
  // The first edge the path from a to b enters, skipping edges skip_a and skip_b.
  Hit first_entry(const Vec2& a, const Vec2& b, int skip_a, int skip_b) const noexcept;
  // Calls visit(edge) for every edge listed in the cells the segment a-b passes through,
  // cell by cell from a, until done(t) is true for the fraction t of the path at which it
  // leaves the cell (an edge may come more than once).
  template <typename Visit, typename Done>
  void for_each_edge_near(const Vec2& a, const Vec2& b, Visit&& visit, Done&& done) const noexcept;
  // Puts the proxy where a hit stopped it: on the edge, or on a vertex near its ends.
  void place(const Hit& hit, Vec2* proxy, ProxyContact* contact, int* feature) const noexcept;

  std::vector<Vec2> vertices_;
  std::vector<Vec2> tangents_;
  std::vector<Vec2> normals_;
  std::vector<double> lengths_m_;
  std::vector<unsigned char> wide_;
  bool solid_inside_{true};
  // The vertices' bounding box grown by a few billionths of its larger side: more than
  // the grid's margin plus any edge's vertex snap, so no crossing lies outside it.
  // (Unbounded for an empty outline, which never moves a proxy.)
  Vec2 reach_low_m_{{-INFINITY, -INFINITY}};
  Vec2 reach_high_m_{{INFINITY, INFINITY}};

  // The grid: cell (c, r) covers [origin + c w, origin + (c + 1) w) x [... r h ...];
  // its edges are cell_edges_[cell_start_[k] .. cell_start_[k + 1]) with k = r columns + c.
  Vec2 origin_m_{};
  double cell_width_m_{1.0};
  double cell_height_m_{1.0};
  int columns_{1};
  int rows_{1};
  std::vector<int> cell_start_;
  std::vector<int> cell_edges_;
};

}  // namespace hapscene
