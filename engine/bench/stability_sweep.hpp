#pragma once
// Stability stress on the simulated Hapkit, through the harness's own verdicts:
//   stiffness sweep: the largest wall stiffness that stays passive (the passivity check
//     of the press, hold and release scenarios), the largest that stays stable (no limit
//     cycle above the harness's 0.2 mm, no growth, while held and after release) and the
//     largest with no persistent motion at all (the stiffness where a small limit cycle
//     first appears), by bisection at each rate, with the profile's Coulomb friction and
//     without it;
//   damping sweep: the largest virtual damping that is neither gritty (the force-jitter
//     check while held and shaken) nor unstable, per velocity estimator, with noise;
//   estimator quality: each estimator's noise and delay on synthetic positions.
#include <string>
#include <vector>

#include "engine/devices/profile.hpp"

namespace hapscene {

// The limits for one setting of the plant's Coulomb friction.
struct WallLimits {
  double coulomb_N{};
  double passive_N_per_m{};          // largest passing stiffness found
  double stable_N_per_m{};
  double quiet_N_per_m{};            // largest with no persistent motion (residual <= one count)
  bool passive_above_range{};        // the top of the search range still passed
  bool stable_above_range{};
  bool quiet_above_range{};
  double bound_N_per_m{};            // min(2 b / T, 2 f_c / D) with this friction
  const char* bound_name{};          // which of the two binds
  double bound_coulomb_N_per_m{};    // 2 f_c / D with this friction
};

struct StiffnessLimits {
  double rate_hz{};
  WallLimits with_coulomb;           // the profile's friction (hapkit3: 0.1 N)
  WallLimits without_coulomb;        // f_c = 0
  double bound_2b_over_T{};          // Colgate and Schenkel: 2 b / T
  double bound_with_hand{};          // the same with the hand's damping added to b
};

struct DampingLimit {
  std::string estimator;
  double smooth_N_s_per_m{};         // largest damping that is neither gritty nor unstable
  bool above_range{};
  std::string first_failure;         // what fails just above it ("hold/jitter", ...)
};

// How an estimator turns sensor positions into velocity, measured on synthetic input.
struct EstimatorQuality {
  std::string estimator;
  double noise_rms_m_per_s{};        // at rest, Gaussian noise rounded to whole counts
  double delay_ticks{};              // phase lag / (omega T) on a 5 Hz sine
  double gain{};                     // amplitude ratio on that sine (1: none lost)
};

// The search ranges: 200 N/m .. 1 MN/m and 0.01 .. 100 N*s/m, to about 1 % (log bisection).
std::vector<StiffnessLimits> sweep_wall_stiffness(const std::vector<double>& rates_hz);
std::vector<DampingLimit> sweep_damping(double rate_hz, double noise_counts);
std::vector<EstimatorQuality> measure_estimators(double rate_hz, double noise_counts);

// The profile the sweeps run on (hapkit3), for reports.
DeviceProfile stress_profile();

}  // namespace hapscene
