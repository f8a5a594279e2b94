#include "engine/harness/planar_validate_scenario.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "engine/base/format.hpp"
#include "engine/harness/planar_route.hpp"
#include "engine/harness/planar_scenario.hpp"
#include "engine/harness/scenario_timing.hpp"

namespace hapscene {
namespace {

using namespace scenario_timing;

constexpr std::size_t kMaxPressPlaces = 16;
constexpr std::size_t kMaxOutlineCandidates = 64;  // edges of one outline measured for places
constexpr double kMinPressDepth_m = 0.001;           // a place the workspace leaves less of is skipped
constexpr double kSwipeGap_m = 0.010;                // swipe: from this far in front, to this far beyond
constexpr double kSwipeSpeed_m_per_s = 0.5;
constexpr double kSwipeBackSpeed_m_per_s = 0.1;
constexpr double kThicknessStep_m = 5e-5;
constexpr double kThicknessReach_m = 0.020;

std::string mm_point(const Vec2& p_m) { return printf_string("(%.1f, %.1f) mm", p_m[0] * 1e3, p_m[1] * 1e3); }

// The solid's thickness from a boundary point inward (infinity past kThicknessReach_m).
double thickness_at(const PlanarShapeGeometry& shape, const Vec2& surface_m, const Vec2& outward) {
  for (double s = kThicknessStep_m; s <= kThicknessReach_m; s += kThicknessStep_m) {
    if (shape.depth_m(surface_m - s * outward) < 0.0) return s;
  }
  return INFINITY;
}

bool inside_box(const Vec2& p, const Vec2& low, const Vec2& high, double margin_m) {
  return p[0] >= low[0] + margin_m && p[0] <= high[0] - margin_m && p[1] >= low[1] + margin_m &&
         p[1] <= high[1] - margin_m;
}

// The hand's path as timed waypoints, built move by move.
class PlanarPathBuilder {
 public:
  explicit PlanarPathBuilder(const Vec2& start_m) : at_(start_m) { points_.push_back({0.0, start_m, true}); }
  void move_to(const Vec2& p_m, double speed_m_per_s) {
    const double length_m = norm(p_m - at_);
    if (!(length_m > 1e-9)) return;
    t_ += length_m / speed_m_per_s;
    at_ = p_m;
    points_.push_back({t_, p_m, true});
  }
  void hold(double duration_s) {
    t_ += duration_s;
    points_.push_back({t_, at_, true});
  }
  void let_go() { points_.back().grip = false; }
  double t_s() const { return t_; }
  const Vec2& at() const { return at_; }
  std::vector<PlanarHandWaypoint> take() { return std::move(points_); }

 private:
  Vec2 at_;
  double t_{};
  std::vector<PlanarHandWaypoint> points_;
};

// Travels to `to_m` round the solids (engine/harness/planar_route.hpp).
void travel(const std::vector<PlanarShapeGeometry>& shapes, const ReachableFree* free, PlanarPathBuilder* path,
            const Vec2& to_m, double speed) {
  for (const Vec2& p : way_round_solids(shapes, free, path->at(), to_m)) path->move_to(p, speed);
}

// The shape nearest home, the point of its boundary nearest home and the normal out of
// its solid there (from home when home is outside the solid).
struct Contact {
  int shape{-1};
  Vec2 surface_m{};
  Vec2 outward{};
};
Contact nearest_contact(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& home_m) {
  Contact c;
  c.shape = nearest_shape_index(shapes, home_m);
  if (c.shape < 0) return c;
  const PlanarShapeGeometry& shape = shapes[static_cast<std::size_t>(c.shape)];
  c.surface_m = shape.nearest_boundary_m(home_m);
  const Vec2 from_surface = home_m - c.surface_m;
  c.outward = shape.depth_m(home_m) < 0.0 ? unit_or(from_surface, outward_at(shape, c.surface_m))
                                          : unit_or(-from_surface, outward_at(shape, c.surface_m));
  return c;
}

// A point moved toward `p` until inside the box shrunk by the margin (for the fallbacks).
Vec2 clamp_to_box(const Vec2& p, const Vec2& low, const Vec2& high) {
  return Vec2{{std::clamp(p[0], low[0] + kWorkspaceMargin_m, high[0] - kWorkspaceMargin_m),
               std::clamp(p[1], low[1] + kWorkspaceMargin_m, high[1] - kWorkspaceMargin_m)}};
}

}  // namespace

std::optional<PlanarValidateKind> planar_validate_kind_named(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kPlanarValidateNames); ++i) {
    if (kPlanarValidateNames[i] == name) return static_cast<PlanarValidateKind>(i);
  }
  return std::nullopt;
}

std::vector<PlanarPressPlace> planar_press_places(const std::vector<PlanarShapeGeometry>& shapes,
                                                  const Vec2& home_m) {
  std::vector<PlanarPressPlace> places;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const PlanarShapeGeometry& shape = shapes[k];
    const int index = static_cast<int>(k);
    auto add = [&](const Vec2& surface, const Vec2& outward, const char* what, bool measure) {
      const double thickness = measure ? thickness_at(shape, surface, outward) : INFINITY;
      places.push_back({index, surface, outward, what, thickness});
    };
    switch (shape.kind) {
      case PlanarShapeKind::wall: add(shape.nearest_boundary_m(home_m), shape.normal, "wall", true); break;
      case PlanarShapeKind::circle:
        for (int q = 0; q < 4; ++q) {
          const double angle = q * 0.5 * 3.14159265358979323846;
          const Vec2 radial{{std::cos(angle), std::sin(angle)}};
          add(shape.center_m + shape.radius_m * radial, shape.solid_inside ? radial : -radial, "rim", true);
        }
        break;
      case PlanarShapeKind::box:
      case PlanarShapeKind::polygon: {
        // Every edge and corner of a small outline; of a large one, kMaxOutlineCandidates
        // spread round it (measuring each costs a scan of the outline, so all of a 10 000-point
        // polygon's would take minutes, and at most kMaxPressPlaces are pressed anyway).
        const std::size_t n = shape.points_m.size();
        const std::size_t stride = std::max<std::size_t>(1, n / kMaxOutlineCandidates);
        const auto edge_out = [&](std::size_t i) {
          return outward_at(shape, (shape.points_m[i] + shape.points_m[(i + 1) % n]) * 0.5);
        };
        for (std::size_t i = 0; i < n; i += stride) {
          const Vec2 out = edge_out(i);
          add(shape.points_m[i], unit_or(edge_out((i + n - 1) % n) + out, out), "corner", false);
          add((shape.points_m[i] + shape.points_m[(i + 1) % n]) * 0.5, out, "edge", true);
        }
        break;
      }
    }
  }
  return places;
}

PlanarValidateScenario build_planar_validate_scenario(PlanarValidateKind kind, const PlanarScene& scene,
                                                      const HarnessOptions& options) {
  PlanarValidateScenario s;
  s.kind = kind;
  s.name = std::string(kPlanarValidateNames[static_cast<int>(kind)]);
  s.start_m = scene.device.home_m;
  PlanarHandConfig& hand = s.hand;
  hand.stiffness_N_per_m = options.hand_stiffness_N_per_m;
  hand.damping_N_s_per_m = options.hand_damping_N_s_per_m;
  hand.mass_kg = options.hand_mass_kg;
  hand.hold_m = s.start_m;
  const Vec2 low = scene.safety.workspace_min_m;
  const Vec2 high = scene.safety.workspace_max_m;
  const std::vector<PlanarShapeGeometry> shapes = planar_scenario_shapes(scene);
  const ValidateThresholds& t = options.thresholds;
  const double press_depth_m = t.press_force_N / options.hand_stiffness_N_per_m;
  PlanarPathBuilder path(s.start_m);
  // Where the hand may go: only needed by the scenarios that travel among the shapes.
  std::optional<ReachableFree> reachable;
  if (!shapes.empty() && (kind == PlanarValidateKind::sweep || kind == PlanarValidateKind::press ||
                          kind == PlanarValidateKind::swipe)) {
    reachable.emplace(shapes, low, high, s.start_m);
  }
  const ReachableFree* free = reachable ? &*reachable : nullptr;

  switch (kind) {
    case PlanarValidateKind::sweep: {
      // The plot's raster (rows from the bottom, serpentine), each point moved out of the
      // solids and each leg routed round them, so the hand covers the free workspace
      // without dragging the handle through a shape.
      const PlanarScenario raster = build_planar_scenario(PlanarScenarioKind::sweep, scene, options);
      const PlanarHandConfig& r = raster.hand;
      // A row end out of the hand's reach (in a wall, or beyond walls round the start)
      // moves along the row to the nearest reachable point; a row with none is left out.
      const int rows = static_cast<int>(std::lround((r.sweep_max_m[1] - r.sweep_min_m[1]) / r.sweep_pitch_m)) + 1;
      int rows_left_out = 0;
      int ends_moved = 0;
      for (int row = 0; row < rows; ++row) {
        const double y = std::min(r.sweep_min_m[1] + row * r.sweep_pitch_m, r.sweep_max_m[1]);
        const bool rightward = row % 2 == 0;
        const double x_first = rightward ? r.sweep_min_m[0] : r.sweep_max_m[0];
        const double x_last = rightward ? r.sweep_max_m[0] : r.sweep_min_m[0];
        std::vector<Vec2> ends;
        for (const double x : {x_first, x_last}) {
          Vec2 end = free_point(shapes, Vec2{{x, y}});
          if (free != nullptr && !free->reachable(end)) {
            // Scan along the row from this end toward the other.
            const int steps = static_cast<int>(std::ceil(std::fabs(x_last - x_first) / kReachCell_m));
            const double sign = (x == x_first) == (x_last > x_first) ? 1.0 : -1.0;
            bool found = false;
            for (int k = 0; k <= steps && !found; ++k) {
              const Vec2 p{{x + sign * k * kReachCell_m, y}};
              if (free->reachable(p) && shapes_clear(shapes, p, kRouteClearance_m)) {
                end = p;
                found = true;
              }
            }
            if (!found) break;
            ++ends_moved;
          }
          ends.push_back(end);
        }
        if (ends.size() < 2) {
          ++rows_left_out;
          continue;
        }
        for (const Vec2& end : ends) travel(shapes, free, &path, end, r.speed_m_per_s);
      }
      hand.motion = PlanarHandMotion::path;
      hand.path = path.take();
      s.duration_s = hand.path.back().t_s + kSettle_s;
      s.description = printf_string("a raster of %d rows over the middle 80 %% of the workspace at %g mm/s, round the solids",
                                    rows, r.speed_m_per_s * 1e3);
      if (rows_left_out + ends_moved > 0) {
        s.description += printf_string(" (within the part the hand reaches from the start: %d rows left out, %d row ends moved)",
                                       rows_left_out, ends_moved);
      }
      return s;
    }
    case PlanarValidateKind::press:
    case PlanarValidateKind::swipe: {
      const bool press = kind == PlanarValidateKind::press;
      if (press && !shapes.empty() && press_depth_m < kMinPressDepth_m) {
        s.applicable = false;
        s.description = printf_string("the press depth, press_force / hand stiffness = %g mm, is under the %g mm a "
                                      "press needs (raise press_force or lower the hand's stiffness)",
                                      press_depth_m * 1e3, kMinPressDepth_m * 1e3);
        return s;
      }
      std::vector<PlanarPressPlace> places = planar_press_places(shapes, s.start_m);
      if (!press) {
        std::erase_if(places, [](const PlanarPressPlace& p) { return !(p.thickness_m <= kThinWidth_m); });
      }
      // A place another shape's solid covers (walls meeting at a junction), or whose point
      // in front the hand cannot reach from the start (in a neighbouring wall, or beyond
      // walls round the start), is no place to press: left out before the spread.
      const std::size_t found = places.size();
      std::erase_if(places, [&](const PlanarPressPlace& p) {
        for (std::size_t k = 0; k < shapes.size(); ++k) {
          if (static_cast<int>(k) != p.shape && shapes[k].depth_m(p.surface_m) > -1e-9) return true;
        }
        const Vec2 approach = p.surface_m + (press ? kApproachGap_m : kSwipeGap_m) * p.outward;
        return free != nullptr && !free->reachable(approach);
      });
      const std::size_t left_out = found - places.size();
      if (places.size() > kMaxPressPlaces) {
        std::vector<PlanarPressPlace> spread;
        for (std::size_t i = 0; i < kMaxPressPlaces; ++i) spread.push_back(places[i * places.size() / kMaxPressPlaces]);
        places = std::move(spread);
      }
      int edges = 0;
      int corners = 0;
      for (const PlanarPressPlace& place : places) {
        const double gap_m = press ? kApproachGap_m : kSwipeGap_m;
        const Vec2 approach = place.surface_m + gap_m * place.outward;
        if (!inside_box(approach, low, high, kWorkspaceMargin_m)) continue;
        double depth_m = press ? press_depth_m : place.thickness_m + kSwipeGap_m;
        while (depth_m >= kMinPressDepth_m && !inside_box(place.surface_m - depth_m * place.outward, low, high, kWorkspaceMargin_m)) {
          depth_m -= 5e-4;
        }
        if (depth_m < kMinPressDepth_m) continue;
        const Vec2 deep = place.surface_m - depth_m * place.outward;
        travel(shapes, free, &path, approach, kMoveSpeed_m_per_s);
        if (press) {
          for (const double speed : kPressSpeeds_m_per_s) {
            path.move_to(deep, speed);
            path.hold(kPressHold_s);
            path.move_to(approach, speed);
          }
        } else {
          path.hold(0.2);
          path.move_to(deep, kSwipeSpeed_m_per_s);
          path.hold(kPressHold_s);
          path.move_to(approach, kSwipeBackSpeed_m_per_s);
        }
        ++(place.what == std::string("corner") ? corners : edges);
      }
      if (edges + corners == 0) {
        s.applicable = false;
        s.description = shapes.empty() ? "no shape to press into"
                        : press        ? "no place of a shape inside the workspace to press into"
                                       : printf_string("no thin place (a solid at most %g mm thick) to swipe across",
                                                       kThinWidth_m * 1e3);
        return s;
      }
      hand.motion = PlanarHandMotion::path;
      hand.path = path.take();
      s.duration_s = hand.path.back().t_s + kSettle_s;
      if (press) {
        s.description = printf_string(
            "hand presses %d edge and %d corner places of %zu shapes, %g mm deep from 3 mm in front at 20, 80, "
            "200 mm/s, holding 300 ms",
            edges, corners, shapes.size(), press_depth_m * 1e3);
      } else {
        s.description = printf_string(
            "hand swipes across %d thin places from 10 mm in front to 10 mm beyond at 500 mm/s, holds 300 ms, "
            "back at 100 mm/s",
            edges);
      }
      if (left_out > 0) {
        s.description += printf_string(" (%zu places covered by another shape or out of the hand's reach left out)", left_out);
      }
      return s;
    }
    case PlanarValidateKind::release:
    case PlanarValidateKind::hold: {
      const bool release = kind == PlanarValidateKind::release;
      const Contact contact = nearest_contact(shapes, s.start_m);
      Vec2 pose;
      std::string where;
      if (contact.shape >= 0) {
        const double depth_m = release ? 0.25 * t.release_from_m : kHoldDepth_m;
        pose = contact.surface_m - depth_m * contact.outward;
        where = printf_string("%g mm into the %s at ", depth_m * 1e3,
                              planar_shape_kind_name(shapes[static_cast<std::size_t>(contact.shape)].kind)) +
                mm_point(contact.surface_m);
      } else {
        pose = s.start_m + Vec2{{release ? t.release_from_m : 0.5 * t.release_from_m, 0.0}};
        where = "at " + mm_point(pose);
      }
      pose = clamp_to_box(pose, low, high);
      path.move_to(pose, kMoveSpeed_m_per_s);
      if (release) {
        path.hold(kReleaseHold_s);
        const double release_s = path.t_s();
        path.let_go();
        s.watch_from_s = release_s;
        s.duration_s = release_s + kReleaseWatch_s;
        s.description = "hand holds the handle " + where + printf_string(" and lets go at %.2f s", release_s);
      } else {
        path.hold(kHoldSettle_s + kHoldWatch_s);
        s.watch_from_s = path.t_s() - kHoldWatch_s;
        s.duration_s = path.t_s();
        s.description = "hand holds still " + where + printf_string(", watched from %.2f s", *s.watch_from_s);
      }
      hand.motion = PlanarHandMotion::path;
      hand.path = path.take();
      return s;
    }
    case PlanarValidateKind::shake: {
      const Contact contact = nearest_contact(shapes, s.start_m);
      hand.motion = PlanarHandMotion::shake;
      hand.shake_direction = contact.shape >= 0 ? -contact.outward : Vec2{{1.0, 0.0}};
      hand.shake_amplitude_m = kShakeAmplitude_m;
      hand.shake_frequency_Hz = kShakeFrequency_Hz;
      s.duration_s = kShakeDuration_s;
      s.description = printf_string("+/-2 mm at 8 Hz around %s along (%.2f, %.2f) for 1.5 s", mm_point(s.start_m).c_str(),
                                    hand.shake_direction[0], hand.shake_direction[1]);
      return s;
    }
    case PlanarValidateKind::free: {
      if (options.free_start_planar_m) s.start_m = *options.free_start_planar_m;
      hand.motion = PlanarHandMotion::none;
      s.duration_s = kFreeDuration_s;
      s.watch_from_s = 0.0;
      s.description = "no hand, handle starts at " + mm_point(s.start_m);
      return s;
    }
  }
  return s;
}

}  // namespace hapscene
