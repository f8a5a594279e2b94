#pragma once
// The closed-loop scenario a 2-DOF figure shows (`hapscene plot` on a planar scene): a
// virtual hand (engine/devices/planar/planar_hand.hpp) moves the simulated device from
// the profile's home over the scene's workspace box (the safety workspace's box, the
// environment's when it narrows the profile's), and the run is traced for the figure.
//   sweep   a raster over the middle 80 % of the box: 7 rows along x, serpentine, at
//           100 mm/s, once
//   press   into the shape nearest the start: to the point of its boundary nearest the
//           start at 50 mm/s, 10 mm on past it at 20 mm/s, a hold of 0.5 s, and back to
//           the start the same way (not applicable without a shape)
//   line    across the middle of the box (its middle 80 % along x) and back, at 50 mm/s
//   circle  one turn of a circle round the middle of the box, its radius a quarter of the
//           box's smaller side, at 50 mm/s
// Each takes the time to travel from the start onto its path and along it once, plus
// 0.3 s. The traced proxy is that of the shape nearest the start.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/devices/planar/planar_hand.hpp"
#include "engine/harness/planar_trace.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/run/runner.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

enum class PlanarScenarioKind { sweep, press, line, circle };

inline constexpr std::string_view kPlanarScenarioNames[] = {"sweep", "press", "line", "circle"};

// Parses a planar scenario name; empty when unknown.
std::optional<PlanarScenarioKind> planar_scenario_kind_named(std::string_view name);

struct PlanarScenario {
  PlanarScenarioKind kind{};
  std::string name;
  std::string description;   // what the hand does, with numbers
  bool applicable{true};     // false: nothing to do (press without a shape)
  double duration_s{};
  Vec2 start_m{};            // the handle's start (the profile's home)
  PlanarHandConfig hand;
  int proxy_index{-1};       // the traced shape (planar_shape_list's order), -1: none
};

// Builds one scenario for `scene`; the hand's grip (stiffness, damping, mass) comes from
// `options` (its 1-D fields, noise and the free start, are not read).
PlanarScenario build_planar_scenario(PlanarScenarioKind kind, const PlanarScene& scene,
                                     const HarnessOptions& options);

struct PlanarScenarioRun {
  std::vector<PlanarTickRecord> records;  // the trace (bucketed for long runs)
  std::uint64_t ticks_per_bucket{1};
  RunSummaryOf<2> summary;
};

// Runs an applicable scenario on the simulated device in simulated time (deterministic:
// the same scene, scenario and seed give the same records). Throws InputError when the
// linkage cannot reach the start.
PlanarScenarioRun run_planar_scenario(const PlanarScene& scene, const PlanarScenario& scenario, std::uint64_t seed);

}  // namespace hapscene
