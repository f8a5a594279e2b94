#include "engine/harness/planar_scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "engine/base/format.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/scenario_timing.hpp"

namespace hapscene {
namespace {

constexpr double kRasterSpeed_m_per_s = 0.1;
constexpr int kSweepRows = 7;
constexpr double kSpeed_m_per_s = 0.05;        // line, circle, press approach
constexpr double kPressSpeed_m_per_s = 0.02;   // into the shape and out
constexpr double kPressDepth_m = 0.010;
constexpr double kShapePressHold_s = 0.5;     // press: held this long at its depth

// Length of a polyline from `start` through `points`.
double path_length_m(const Vec2& start_m, const std::vector<Vec2>& points_m) {
  double length_m = 0.0;
  Vec2 previous = start_m;
  for (const Vec2& p : points_m) {
    length_m += norm(p - previous);
    previous = p;
  }
  return length_m;
}

}  // namespace

std::optional<PlanarScenarioKind> planar_scenario_kind_named(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kPlanarScenarioNames); ++i) {
    if (kPlanarScenarioNames[i] == name) return static_cast<PlanarScenarioKind>(i);
  }
  return std::nullopt;
}

PlanarScenario build_planar_scenario(PlanarScenarioKind kind, const PlanarScene& scene,
                                     const HarnessOptions& options) {
  PlanarScenario s;
  s.kind = kind;
  s.name = std::string(kPlanarScenarioNames[static_cast<int>(kind)]);
  s.start_m = scene.device.home_m;
  const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(scene);
  s.proxy_index = nearest_shape_index(shapes, s.start_m);

  PlanarHandConfig& hand = s.hand;
  hand.stiffness_N_per_m = options.hand_stiffness_N_per_m;
  hand.damping_N_s_per_m = options.hand_damping_N_s_per_m;
  hand.mass_kg = options.hand_mass_kg;
  hand.hold_m = s.start_m;
  const Vec2 low = scene.safety.workspace_min_m;
  const Vec2 high = scene.safety.workspace_max_m;
  const Vec2 middle = (low + high) * 0.5;
  const Vec2 margin = (high - low) * 0.1;
  double travel_m = 0.0;
  double speed_m_per_s = kSpeed_m_per_s;
  switch (kind) {
    case PlanarScenarioKind::sweep: {
      hand.motion = PlanarHandMotion::sweep;
      hand.speed_m_per_s = speed_m_per_s = kRasterSpeed_m_per_s;
      hand.sweep_min_m = low + margin;
      hand.sweep_max_m = high - margin;
      hand.sweep_pitch_m = (hand.sweep_max_m[1] - hand.sweep_min_m[1]) / (kSweepRows - 1);
      // The hand's own raster (planar_hand.cpp): rows from the bottom, serpentine.
      std::vector<Vec2> points;
      for (int row = 0; row < kSweepRows; ++row) {
        const double y = std::min(hand.sweep_min_m[1] + row * hand.sweep_pitch_m, hand.sweep_max_m[1]);
        const bool rightward = row % 2 == 0;
        points.push_back(Vec2{{rightward ? hand.sweep_min_m[0] : hand.sweep_max_m[0], y}});
        points.push_back(Vec2{{rightward ? hand.sweep_max_m[0] : hand.sweep_min_m[0], y}});
      }
      travel_m = path_length_m(s.start_m, points);
      s.description = printf_string("a raster of 7 rows over the middle 80 %% of the workspace at %g mm/s",
                                    speed_m_per_s * 1e3);
      break;
    }
    case PlanarScenarioKind::line: {
      hand.motion = PlanarHandMotion::line;
      hand.speed_m_per_s = speed_m_per_s;
      hand.line_from_m = Vec2{{low[0] + margin[0], middle[1]}};
      hand.line_to_m = Vec2{{high[0] - margin[0], middle[1]}};
      hand.line_back_and_forth = true;
      travel_m = path_length_m(s.start_m, {hand.line_from_m, hand.line_to_m, hand.line_from_m});
      s.description = printf_string("across the workspace at y = %.1f mm and back at %g mm/s", middle[1] * 1e3,
                                    speed_m_per_s * 1e3);
      break;
    }
    case PlanarScenarioKind::circle: {
      hand.motion = PlanarHandMotion::circle;
      hand.speed_m_per_s = speed_m_per_s;
      hand.circle_center_m = middle;
      hand.circle_radius_m = 0.25 * std::min(high[0] - low[0], high[1] - low[1]);
      const Vec2 first = middle + Vec2{{hand.circle_radius_m, 0.0}};
      travel_m = norm(first - s.start_m) + 2.0 * std::numbers::pi * hand.circle_radius_m;
      s.description = printf_string("one turn of radius %.1f mm round (%.1f, %.1f) mm at 50 mm/s", hand.circle_radius_m * 1e3,
                                    middle[0] * 1e3, middle[1] * 1e3);
      break;
    }
    case PlanarScenarioKind::press: {
      if (s.proxy_index < 0) {
        s.applicable = false;
        s.description = "no shape to press into";
        return s;
      }
      const PlanarShapeGeometry& shape = shapes[static_cast<std::size_t>(s.proxy_index)];
      const Vec2 surface_m = shape.nearest_boundary_m(s.start_m);
      const Vec2 approach = surface_m - s.start_m;
      const double approach_m = norm(approach);
      // Into the shape along the approach; from on its boundary, into a wall's solid or
      // toward a circle's centre (a box's or polygon's inside: toward the first point).
      Vec2 inward = approach_m > 1e-9 ? approach / approach_m : Vec2{};
      if (!(approach_m > 1e-9)) {
        const Vec2 toward = shape.kind == PlanarShapeKind::wall     ? -shape.normal
                            : shape.kind == PlanarShapeKind::circle ? shape.center_m - s.start_m
                                                                    : shape.points_m[0] - s.start_m;
        inward = norm(toward) > 0.0 ? toward / norm(toward) : Vec2{{1.0, 0.0}};
      }
      const Vec2 deep_m = surface_m + kPressDepth_m * inward;
      const double t_surface = approach_m / kSpeed_m_per_s;
      const double t_deep = t_surface + kPressDepth_m / kPressSpeed_m_per_s;
      const double t_held = t_deep + kShapePressHold_s;
      const double t_out = t_held + kPressDepth_m / kPressSpeed_m_per_s;
      const double t_back = t_out + t_surface;
      hand.motion = PlanarHandMotion::path;
      hand.path = {{0.0, s.start_m, true}};
      if (t_surface > 0.0) hand.path.push_back({t_surface, surface_m, true});
      hand.path.push_back({t_deep, deep_m, true});
      hand.path.push_back({t_held, deep_m, true});
      hand.path.push_back({t_out, surface_m, true});
      if (t_back > t_out) hand.path.push_back({t_back, s.start_m, true});
      s.duration_s = t_back + scenario_timing::kSettle_s;
      s.description = std::string("into the ") + planar_shape_kind_name(shape.kind) +
                      printf_string(" at (%.1f, %.1f) mm, 10 mm deep, held 0.5 s, and back", surface_m[0] * 1e3,
                                    surface_m[1] * 1e3);
      return s;
    }
  }
  s.duration_s = travel_m / speed_m_per_s + scenario_timing::kSettle_s;
  return s;
}

PlanarScenarioRun run_planar_scenario(const PlanarScene& scene, const PlanarScenario& scenario, std::uint64_t seed) {
  PlanarSimulationConfig simulation;
  simulation.hand = scenario.hand;
  simulation.noise_seed = seed;
  simulation.start_q_rad = planar_joint_angles_at(scene.device, scenario.start_m);
  const auto device = std::make_unique<SimulatedPlanar>(scene.device, simulation);
  RunOptions options;
  options.duration_s = scenario.duration_s;
  options.pacing = Pacing::simulated_time;
  const auto ticks = static_cast<std::uint64_t>(std::llround(scenario.duration_s * scene.rate_hz));
  PlanarTrace trace(device->truth(), ticks, scenario.proxy_index);
  PlanarScenarioRun run;
  run.summary = run_scene(scene, *device, options, &trace);
  run.records = trace.records();
  run.ticks_per_bucket = trace.ticks_per_bucket();
  return run;
}

}  // namespace hapscene
