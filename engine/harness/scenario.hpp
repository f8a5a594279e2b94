#pragma once
// The harness's virtual-hand scenarios, each named, deterministic and built from the
// scene (its workspace, and the stiff regions its force field has):
//   sweep    the hand moves slowly across the whole workspace and back;
//   press    the hand pushes into every stiff region's edge at several speeds, holds,
//            backs out (not applicable when the field has no stiff region);
//   release  the hand displaces the handle, holds it, and lets go;
//   hold     the hand holds still in the field (in contact with the first wall, if any);
//   shake    a fast small oscillation of the hand around the start;
//   free     no hand at all, from a given start.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/harness/force_field.hpp"
#include "engine/load/validate_thresholds.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

enum class ScenarioKind { sweep, press, release, hold, shake, free };

inline constexpr std::string_view kScenarioNames[] = {"sweep", "press", "release",
                                                      "hold",  "shake", "free"};

// Options shared by every scenario (the command line's --hand-*, --noise, --seed, --start),
// and the thresholds of the environment's "validate" block (Environment::validate).
struct HarnessOptions {
  double hand_stiffness_N_per_m{200.0};  // a relaxed grip on the paddle
  double hand_damping_N_s_per_m{2.0};
  double hand_mass_kg{0.02};             // a finger's effective mass, moving with the paddle
  double noise_counts{-1.0};             // sensor noise; < 0: the profile's
  std::uint64_t seed{1};
  double free_start_m{0.004};            // free: where the handle starts (home period)
  std::optional<Vec2> free_start_planar_m{};  // free on a 2-DOF scene (empty: the profile's home)
  ValidateThresholds thresholds;         // how scenarios are built and judged
};

struct Scenario {
  ScenarioKind kind{};
  std::string name;
  std::string description;    // what the hand does, with numbers
  bool applicable{true};      // false: nothing to do in this scene (press without walls)
  double duration_s{};
  SimulationConfig simulation;
  // Oscillation is watched from this time to the end (the hand has let go, or holds
  // still); empty when the scenario has no such window.
  std::optional<double> watch_from_s;
};

// Parses a scenario name; empty when unknown.
std::optional<ScenarioKind> scenario_kind_named(std::string_view name);

// Builds one scenario for `scene` whose force field was probed as `field`.
Scenario build_scenario(ScenarioKind kind, const Scene& scene, const ForceField& field,
                        const HarnessOptions& options);

}  // namespace hapscene
