#pragma once
// Integration error of the simulated 2-DOF plant (engine/devices/planar/planar_plant.hpp),
// as `bench --accuracy` measures the 1-D plant's: a scenario runs as a loop at a rate (the
// rendered force computed from the true handle position each tick, mapped to joint torques
// by J^T at that tick and held, an ideal sensor and drive), with an integrator and a
// substep count, and is compared at the ticks with the same loop whose plant is integrated
// by RK4 at much finer steps. Scenarios, around the device's home handle position:
//   release  a 200 N/m spring to the home position, released from 8 mm right and 5 mm down
//            of it (viscous friction, no Coulomb friction, no hand), 1 s;
//   circle   the hand (500 N/m, 5 N s/m) draws a 15 mm circle at 0.1 m/s with no field,
//            Coulomb friction on: the joints reverse, stick and slip, 1.5 s;
//   wall     the hand (2000 N/m, 10 N s/m) drives the handle diagonally at 0.1 m/s into a
//            1000 N/m wall 10 mm away and 10 mm beyond it, holds 0.1 s and comes back,
//            Coulomb friction on.
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/devices/planar/planar_plant.hpp"
#include "engine/devices/planar/planar_plant_examples.hpp"
#include "engine/devices/planar/planar_profile.hpp"

namespace hapscene {

enum class PlanarAccuracyScenario : std::uint8_t { release, circle, wall };

inline constexpr std::string_view kPlanarAccuracyScenarioNames[] = {"release", "circle", "wall"};

struct PlanarAccuracyCase {
  PlanarAccuracyScenario scenario{};
  double rate_hz{1000.0};
  PlanarIntegrator integrator{PlanarIntegrator::rk4};
  int substeps{2};
};

struct PlanarAccuracyResult {
  PlanarAccuracyCase which;
  double run_time_s_per_s{};    // CPU time per simulated second (best of a few repeats)
  double integration_rms_m{};   // handle position against the fine run, at the ticks
  double integration_max_m{};
  double travel_m{};            // the fine run's handle path length (for scale)
  bool finite{true};            // false: the run blew up (or left the linkage's range)
};

struct PlanarAccuracyOptions {
  double fine_step_s{1e-6};     // the reference's RK4 step (at most)
  bool timed{true};             // false: one run per case, run time not measured
};

// Runs every case on one device (parameters and home pose). The fine run is computed once
// per scenario and rate.
std::vector<PlanarAccuracyResult> run_planar_accuracy(const PlanarPlantExample& device,
                                                      const std::vector<PlanarAccuracyCase>& cases,
                                                      const PlanarAccuracyOptions& options = {});

// A shipped or given planar profile as the device of these runs: its plant's parameters
// (engine/devices/planar/simulated_planar.hpp) and the joint angles of its home pose.
// Throws InputError when the home pose cannot be reached.
PlanarPlantExample planar_accuracy_device(const PlanarProfile& profile);

// The default sweep: every scenario at 500 Hz .. 5 kHz, each integrator at 1, 2, 4 and 8
// substeps.
std::vector<PlanarAccuracyCase> default_planar_accuracy_cases();

}  // namespace hapscene
