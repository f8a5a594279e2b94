#include "engine/harness/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/harness/scenario_timing.hpp"

namespace hapscene {
namespace {

using namespace scenario_timing;

constexpr double kSweepSpeed_m_per_s = 0.05;
constexpr int kMaxPressedEdges = 4;

// Builds a "path" hand motion move by move.
class PathBuilder {
 public:
  explicit PathBuilder(double start_m) { points_.push_back({0.0, start_m, true}); }
  void move_to(double x_m, double speed_m_per_s) {
    const double distance_m = std::abs(x_m - points_.back().x_m);
    if (distance_m > 0.0) points_.push_back({now_s() + distance_m / speed_m_per_s, x_m, true});
  }
  void hold(double duration_s) { points_.push_back({now_s() + duration_s, points_.back().x_m, true}); }
  void let_go() { points_.push_back({now_s(), points_.back().x_m, false}); }
  double now_s() const { return points_.back().t_s; }
  std::vector<HandWaypoint> take() { return std::move(points_); }

 private:
  std::vector<HandWaypoint> points_;
};

// An edge the hand can press: where it is and which way is "into" the stiff region.
struct Edge {
  double x_m;
  int into;  // +1: the region is above, -1: below
};

std::vector<Edge> pressable_edges(const ForceField& field) {
  std::vector<Edge> edges;
  for (const StiffRegion& region : field.regions) {
    if (region.low_is_edge) edges.push_back({region.low_m, +1});
    if (region.high_is_edge) edges.push_back({region.high_m, -1});
    // Stiff across the whole workspace (a stiff spring): press from the start both ways.
    if (!region.low_is_edge && !region.high_is_edge) {
      edges.push_back({0.0, +1});
      edges.push_back({0.0, -1});
    }
  }
  std::stable_sort(edges.begin(), edges.end(),
                   [](const Edge& a, const Edge& b) { return std::abs(a.x_m) < std::abs(b.x_m); });
  if (edges.size() > kMaxPressedEdges) edges.resize(kMaxPressedEdges);
  return edges;
}

std::string mm(double x_m) {
  char text[32];
  std::snprintf(text, sizeof text, "%g mm", std::round(x_m * 1e4) / 10.0);
  return text;
}

}  // namespace

std::optional<ScenarioKind> scenario_kind_named(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kScenarioNames); ++i) {
    if (kScenarioNames[i] == name) return static_cast<ScenarioKind>(i);
  }
  return std::nullopt;
}

Scenario build_scenario(ScenarioKind kind, const Scene& scene, const ForceField& field,
                        const HarnessOptions& options) {
  Scenario scenario;
  scenario.kind = kind;
  scenario.name = std::string(kScenarioNames[static_cast<int>(kind)]);
  HandConfig& hand = scenario.simulation.hand;
  hand.stiffness_N_per_m = options.hand_stiffness_N_per_m;
  hand.damping_N_s_per_m = options.hand_damping_N_s_per_m;
  hand.mass_kg = options.hand_mass_kg;
  hand.motion = HandMotion::path;
  scenario.simulation.noise_seed = options.seed;
  const double low_m = scene.safety.workspace_min_m + kWorkspaceMargin_m;
  const double high_m = scene.safety.workspace_max_m - kWorkspaceMargin_m;
  const auto inside = [&](double x_m) { return std::clamp(x_m, low_m, high_m); };
  const ValidateThresholds& limits = options.thresholds;
  PathBuilder path(0.0);

  switch (kind) {
    // Up to the top of the workspace, down to the bottom, back to the start.
    case ScenarioKind::sweep:
      path.move_to(high_m, kSweepSpeed_m_per_s);
      path.move_to(low_m, kSweepSpeed_m_per_s);
      path.move_to(0.0, kSweepSpeed_m_per_s);
      path.hold(0.2);
      scenario.description = "hand sweeps " + mm(low_m) + " .. " + mm(high_m) + " at " +
                             mm(kSweepSpeed_m_per_s) + "/s and back";
      break;

    // Each edge: approach, press in at each speed far enough for press_force, hold, back out.
    case ScenarioKind::press: {
      const std::vector<Edge> edges = pressable_edges(field);
      if (edges.empty()) {
        scenario.applicable = false;
        scenario.description = "no region stiffer than " +
                               std::to_string(static_cast<int>(limits.stiff_threshold_N_per_m)) +
                               " N/m to press";
        break;
      }
      const double depth_m = limits.press_force_N / options.hand_stiffness_N_per_m;
      scenario.description = "hand presses";
      for (const Edge& edge : edges) {
        const double approach_m = inside(edge.x_m - edge.into * kApproachGap_m);
        const double target_m = inside(edge.x_m + edge.into * depth_m);
        path.move_to(approach_m, kMoveSpeed_m_per_s);
        for (const double speed_m_per_s : kPressSpeeds_m_per_s) {
          path.move_to(target_m, speed_m_per_s);
          path.hold(kPressHold_s);
          path.move_to(approach_m, speed_m_per_s);
        }
        scenario.description += " " + std::string(edge.into > 0 ? "up" : "down") + " into " + mm(edge.x_m);
      }
      scenario.description += " at 20, 80, 200 mm/s (" + mm(depth_m) + " beyond the edge), holding " +
                              std::to_string(static_cast<int>(kPressHold_s * 1000)) + " ms";
      path.move_to(0.0, kMoveSpeed_m_per_s);
      path.hold(0.1);
      break;
    }

    // Displace, hold, let go, watch the free motion.
    case ScenarioKind::release: {
      const double target_m = inside(limits.release_from_m);
      path.move_to(target_m, kMoveSpeed_m_per_s);
      path.hold(kReleaseHold_s);
      scenario.watch_from_s = path.now_s();
      path.let_go();
      path.hold(kReleaseWatch_s);
      char at[32];
      std::snprintf(at, sizeof at, "%.2f s", *scenario.watch_from_s);
      scenario.description = "hand holds the handle at " + mm(target_m) + " and lets go at " + at;
      break;
    }

    // Hold still: in contact with the nearest wall if there is one, else half-way to
    // the release point (in the field of a spring).
    case ScenarioKind::hold: {
      const std::vector<Edge> edges = pressable_edges(field);
      const double target_m = edges.empty() ? inside(limits.release_from_m / 2.0)
                                            : inside(edges[0].x_m + edges[0].into * kHoldDepth_m);
      path.move_to(target_m, kMoveSpeed_m_per_s);
      scenario.watch_from_s = path.now_s() + kHoldSettle_s;
      path.hold(kHoldSettle_s + kHoldWatch_s);
      scenario.description = "hand holds still at " + mm(target_m);
      break;
    }

    case ScenarioKind::shake:
      hand.motion = HandMotion::shake;
      hand.hold_m = 0.0;
      hand.shake_amplitude_m = kShakeAmplitude_m;
      hand.shake_frequency_Hz = kShakeFrequency_Hz;
      scenario.duration_s = kShakeDuration_s;
      scenario.description = "hand shakes +/-" + mm(kShakeAmplitude_m) + " at " +
                             std::to_string(static_cast<int>(kShakeFrequency_Hz)) + " Hz around 0 mm";
      return scenario;

    case ScenarioKind::free:
      hand.motion = HandMotion::none;
      scenario.simulation.start_x_m = options.free_start_m;
      scenario.duration_s = kFreeDuration_s;
      scenario.watch_from_s = 0.0;
      scenario.description = "no hand, handle starts at " + mm(options.free_start_m);
      return scenario;
  }
  scenario.duration_s = path.now_s();
  hand.path = path.take();
  return scenario;
}

}  // namespace hapscene
