// The shapes' closed loops (wall, circle) and open-loop formulas (box), and whether each
// can act within a rectangular workspace.
#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/base/polygon.hpp"
#include "engine/effects/planar/planar_shapes.hpp"

namespace hapscene {

Vec2 PlanarWall::force_N(const PlanarInput& in, PlanarProxyState& state) const noexcept {
  if (!all_finite(in.x_m)) return Vec2{};
  const double d = depth_m(in.x_m);
  const bool in_solid = d > 0.0;
  if (!state.started) {
    state = PlanarProxyState{};
    state.started = true;
    state.passive = in_solid;
  }
  if (state.passive && in_solid) {
    state.proxy_m = in.x_m;
    state.contact = ProxyContact::none;
    return Vec2{};
  }
  state.passive = false;
  state.proxy_m = open_loop_proxy_m(in.x_m);
  state.contact = in_solid ? ProxyContact::surface : ProxyContact::none;
  return open_loop_force_N(in);
}

bool PlanarWall::can_act_within(const Vec2& min_m, const Vec2& max_m) const noexcept {
  if (stiffness_N_per_m == 0.0) return false;
  // Some corner of the workspace is in the solid.
  for (const double x : {min_m[0], max_m[0]}) {
    for (const double y : {min_m[1], max_m[1]}) {
      if (depth_m(Vec2{{x, y}}) > 0.0) return true;
    }
  }
  return false;
}

PlanarBox PlanarBox::make(const Vec2& min_m, const Vec2& max_m, double stiffness_N_per_m, bool solid_inside) {
  PlanarBox box;
  box.min_m = min_m;
  box.max_m = max_m;
  box.stiffness_N_per_m = stiffness_N_per_m;
  box.solid_inside = solid_inside;
  // Edges 0 to 3: bottom, right, top, left.
  box.outline = PolygonOutline({min_m, Vec2{{max_m[0], min_m[1]}}, max_m, Vec2{{min_m[0], max_m[1]}}}, solid_inside);
  return box;
}

Vec2 PlanarBox::open_loop_proxy_m(const Vec2& x_m) const noexcept {
  if (!solid_inside) {
    return Vec2{{std::clamp(x_m[0], min_m[0], max_m[0]), std::clamp(x_m[1], min_m[1], max_m[1])}};
  }
  const bool inside = min_m[0] < x_m[0] && x_m[0] < max_m[0] && min_m[1] < x_m[1] && x_m[1] < max_m[1];
  if (!inside) return x_m;
  const double left = x_m[0] - min_m[0];
  const double right = max_m[0] - x_m[0];
  const double bottom = x_m[1] - min_m[1];
  const double top = max_m[1] - x_m[1];
  const double nearest = std::min({left, right, bottom, top});
  if (left == nearest) return Vec2{{min_m[0], x_m[1]}};
  if (right == nearest) return Vec2{{max_m[0], x_m[1]}};
  if (bottom == nearest) return Vec2{{x_m[0], min_m[1]}};
  return Vec2{{x_m[0], max_m[1]}};
}

bool PlanarBox::can_act_within(const Vec2& low_m, const Vec2& high_m) const noexcept {
  if (stiffness_N_per_m == 0.0) return false;
  if (solid_inside) {
    return min_m[0] < high_m[0] && low_m[0] < max_m[0] && min_m[1] < high_m[1] && low_m[1] < max_m[1];
  }
  // A cage acts where the workspace reaches out of the box.
  return low_m[0] < min_m[0] || high_m[0] > max_m[0] || low_m[1] < min_m[1] || high_m[1] > max_m[1];
}

Vec2 PlanarCircle::open_loop_proxy_m(const Vec2& x_m) const noexcept {
  const double dx = x_m[0] - center_m[0];
  const double dy = x_m[1] - center_m[1];
  const double distance = std::sqrt(dx * dx + dy * dy);
  const bool in_solid = solid_inside ? distance < radius_m : distance > radius_m;
  if (!in_solid) return x_m;
  if (distance == 0.0) return Vec2{{center_m[0] + radius_m, center_m[1]}};
  return Vec2{{center_m[0] + dx * (radius_m / distance), center_m[1] + dy * (radius_m / distance)}};
}

namespace {

// Where the path a -> b enters the disc of radius r about the origin (a, b relative to the
// centre; a outside the disc), put on the circle; false when the path does not enter it.
bool path_enters_disc(const Vec2& a, const Vec2& b, double radius_m, Vec2* on_circle_m) noexcept {
  const Vec2 d = b - a;
  const double dd = dot(d, d);
  const double ad = dot(a, d);
  const double excess = dot(a, a) - radius_m * radius_m;  // >= 0 outside the disc
  // Heading in, and the path's line passing closer to the centre than r.
  if (!(ad < 0.0) || !(excess * dd < ad * ad)) return false;
  const double t = std::fmax(0.0, (-ad - std::sqrt(ad * ad - dd * excess)) / dd);
  if (!(t <= 1.0)) return false;  // it would enter beyond b
  Vec2 unit;
  if (!unit_vector(a + d * t, &unit)) return false;
  *on_circle_m = unit * radius_m;
  return true;
}

}  // namespace

Vec2 PlanarCircle::force_N(const PlanarInput& in, PlanarProxyState& state) const noexcept {
  if (!all_finite(in.x_m)) return Vec2{};
  const double dx = in.x_m[0] - center_m[0];
  const double dy = in.x_m[1] - center_m[1];
  const double distance = std::sqrt(dx * dx + dy * dy);
  const bool in_solid = solid_inside ? distance < radius_m : distance > radius_m;
  if (!state.started) {
    state = PlanarProxyState{};
    state.proxy_m = in.x_m;
    state.started = true;
    state.passive = in_solid;
  }
  // Started in the solid: the proxy follows the handle until it has left. Out of the
  // solid a cage's proxy is the handle (a free path inside a disc stays inside it).
  if (state.passive || (!solid_inside && !in_solid)) {
    state.passive = state.passive && in_solid;
    state.proxy_m = in.x_m;
    state.contact = ProxyContact::none;
    return Vec2{};
  }
  // The circle's point nearest the handle: the open loop's formula, from the distance
  // found above (for distance > 0).
  const auto nearest_on_circle = [&] {
    return Vec2{{center_m[0] + dx * (radius_m / distance), center_m[1] + dy * (radius_m / distance)}};
  };
  // A cage's solid (beyond the circle) has no far side: its proxy is the circle's point
  // nearest the handle, where any free path to the handle leaves the disc.
  if (!solid_inside) {
    state.proxy_m = nearest_on_circle();
    state.contact = ProxyContact::surface;
    return proxy_force_N(stiffness_N_per_m, state.proxy_m, in.x_m);
  }
  const Vec2 x_c{{dx, dy}};  // the handle, from the centre
  // A disc. A free proxy moves straight toward the handle and stops where its path enters
  // the disc, however fast the handle went (through the disc and out within one tick too).
  if (state.contact != ProxyContact::surface) {
    const Vec2 from_c = state.proxy_m - center_m;
    // Off the disc, and moved no farther than its gap to the circle: no point of the path
    // can be in the disc (the common case, in a few instructions).
    const Vec2 moved = x_c - from_c;
    const double gap_m = distance - radius_m;
    if (!in_solid && dot(moved, moved) <= gap_m * gap_m) {
      state.proxy_m = in.x_m;
      return Vec2{};
    }
    Vec2 entry_c;
    if (!path_enters_disc(from_c, x_c, radius_m, &entry_c)) {
      if (!in_solid) {
        state.proxy_m = in.x_m;
        return Vec2{};
      }
      entry_c = open_loop_proxy_m(in.x_m) - center_m;  // (rounding put the proxy a hair inside)
    }
    state.proxy_m = center_m + entry_c;
    state.contact = ProxyContact::surface;
  }
  // On the circle at q. The proxy slides along the circle toward the handle but never a
  // quarter turn or more: to the circle's point nearest the handle when that is less than
  // a quarter turn from q, else it holds at q, on the side the handle came in from, however
  // far through the disc it went. Out of the disc, it leaves the circle for the handle when
  // a slide of less than a quarter turn puts the handle in view: the handle less than a
  // quarter turn round, or beside the disc rather than behind it.
  const Vec2 q = state.proxy_m - center_m;
  const double toward = dot(q, x_c);  // > 0: the handle less than a quarter turn round
  if (in_solid) {
    if (toward > 0.0 && distance > 0.0) state.proxy_m = nearest_on_circle();
    return proxy_force_N(stiffness_N_per_m, state.proxy_m, in.x_m);
  }
  if (toward > 0.0 || std::fabs(cross(q, x_c)) >= radius_m * norm(q)) {
    state.proxy_m = in.x_m;
    state.contact = ProxyContact::none;
    return Vec2{};
  }
  return proxy_force_N(stiffness_N_per_m, state.proxy_m, in.x_m);
}

bool PlanarCircle::can_act_within(const Vec2& min_m, const Vec2& max_m) const noexcept {
  if (stiffness_N_per_m == 0.0) return false;
  if (solid_inside) {
    // The disc reaches the workspace: the workspace's point nearest the centre is inside.
    const double nx = std::clamp(center_m[0], min_m[0], max_m[0]) - center_m[0];
    const double ny = std::clamp(center_m[1], min_m[1], max_m[1]) - center_m[1];
    return nx * nx + ny * ny < radius_m * radius_m;
  }
  // A cage acts where the workspace reaches out of the disc: its farthest corner.
  const double fx = std::max(std::fabs(min_m[0] - center_m[0]), std::fabs(max_m[0] - center_m[0]));
  const double fy = std::max(std::fabs(min_m[1] - center_m[1]), std::fabs(max_m[1] - center_m[1]));
  return fx * fx + fy * fy > radius_m * radius_m;
}

namespace {

// Whether p is inside the outline's polygon (crossing number).
bool inside_outline(const PolygonOutline& outline, const Vec2& p) noexcept {
  bool inside = false;
  const int n = outline.edge_count();
  for (int i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = outline.vertex(i);
    const Vec2& b = outline.vertex(j);
    if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]) {
      inside = !inside;
    }
  }
  return inside;
}

}  // namespace

bool PlanarPolygon::can_act_within(const Vec2& min_m, const Vec2& max_m) const noexcept {
  if (stiffness_N_per_m == 0.0) return false;
  const int n = outline.edge_count();
  // An edge in or across the box: the polygon's inside and outside both reach the box.
  for (int i = 0; i < n; ++i) {
    if (segment_meets_box(outline.vertex(i), outline.vertex((i + 1) % n), min_m, max_m, BoxSides::closed)) return true;
  }
  // No edge meets the box: the box lies wholly inside the polygon or wholly outside it.
  const bool box_inside = inside_outline(outline, min_m);
  return outline.solid_inside() ? box_inside : !box_inside;
}

}  // namespace hapscene
