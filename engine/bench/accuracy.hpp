#pragma once
// Run time against error of the simulated Hapkit: scenarios with a known answer, run at a
// loop rate with a plant integrator and substep count, and compared with the truth.
//   release  a spring rendered on the bare plant (mass m, viscous b, no Coulomb friction),
//            released from rest: the truth is the continuous mass-spring-damper, so the
//            frequency and the decay rate are known in closed form;
//   wall     a stiff hand drives the handle at a fixed speed into a wall and back
//            (Coulomb friction on): the truth is a 100 kHz loop integrated with RK4 at
//            1 us steps.
// The rendered force is computed from the true position at each tick and held (an ideal
// sensor and motor), so what is measured is the simulation and the loop rate, not the
// Hapkit's 12 um counts or its 8-bit PWM.
#include <string>
#include <vector>

#include "engine/devices/hapkit_plant.hpp"

namespace hapscene {

// Each case is repeated until its runs took this much CPU time in all (1-D and 2-D).
inline constexpr double kAccuracyMinTimedRun_s = 0.02;

enum class AccuracyScenario { release, wall };

struct AccuracyCase {
  AccuracyScenario scenario{};
  double rate_hz{};
  PlantIntegrator integrator{};
  int substeps{};
};

struct AccuracyResult {
  AccuracyCase which;
  double run_time_s_per_s{};      // CPU time per simulated second (best of repeats)
  double position_rms_m{};        // against the truth, at the ticks
  double force_rms_N{};           // rendered (held) force against the truth's force
  double frequency_error{};       // release: (measured - analytic) / analytic
  double decay_error{};           // release: (measured - analytic) / analytic decay rate
  double integration_rms_m{};     // against the same loop rate with a fine integrator
  bool finite{true};              // false: the run blew up
  bool front_truth{};             // on the scenario's front: run time against position_rms
  bool front_integration{};       // on the front at this loop rate: run time against integration_rms
};

// The scenario's constants, for reports.
struct AccuracySetup {
  double mass_kg{};
  double viscous_N_s_per_m{};
  double spring_N_per_m{};        // release
  double start_m{};
  double analytic_frequency_Hz{};
  double analytic_decay_per_s{};
  double wall_N_per_m{};          // wall
  double wall_m{};
  double speed_m_per_s{};
  double hand_N_per_m{};
  double hand_N_s_per_m{};
};

AccuracySetup accuracy_setup(const DeviceProfile& profile);

// Runs every case (scenario x rate x integrator x substeps) and marks the Pareto fronts.
std::vector<AccuracyResult> run_accuracy_sweep(const DeviceProfile& profile,
                                               const std::vector<AccuracyCase>& cases);

// The default sweep: both scenarios at 250 Hz .. 20 kHz, each integrator at 1, 2, 5, 10
// and 20 substeps.
std::vector<AccuracyCase> default_accuracy_cases();

// Marks which results are on a front, where no other result is both faster and more
// accurate (non-finite runs are never on one): against the truth among all results of a
// scenario, and against the fine integrator among those of a scenario and loop rate.
void mark_pareto_fronts(std::vector<AccuracyResult>* results);

}  // namespace hapscene
