#pragma once
// Stability stress on the simulated Hapkit, through the harness's own verdicts:
//   stiffness sweep: the largest wall stiffness that stays passive (the passivity check
//     of the press, hold and release scenarios) and the largest that stays stable (no
//     limit cycle, no growth while held and after release), by bisection at each rate;
//   damping sweep: the largest virtual damping that is neither gritty (the force-jitter
//     check while held and shaken) nor unstable, per velocity estimator, with noise.
#include <string>
#include <vector>

#include "engine/devices/profile.hpp"

namespace hapscene {

struct StiffnessLimits {
  double rate_hz{};
  double passive_N_per_m{};          // largest passing stiffness found
  double stable_N_per_m{};
  bool passive_above_range{};        // the top of the search range still passed
  bool stable_above_range{};
  double bound_2b_over_T{};          // Colgate and Schenkel: 2 b / T
  double bound_with_hand{};          // the same with the hand's damping added to b
  double bound_coulomb{};            // Abbott and Okamura: 2 f_c / D
};

struct DampingLimit {
  std::string estimator;
  double smooth_N_s_per_m{};         // largest damping that is neither gritty nor unstable
  bool above_range{};
  std::string first_failure;         // what fails just above it ("hold/jitter", ...)
};

// The search ranges: 200 N/m .. 1 MN/m and 0.01 .. 100 N*s/m, to about 1 % (log bisection).
std::vector<StiffnessLimits> sweep_wall_stiffness(const std::vector<double>& rates_hz);
std::vector<DampingLimit> sweep_damping(double rate_hz, double noise_counts);

// The profile the sweeps run on (hapkit3), for reports.
DeviceProfile stress_profile();

}  // namespace hapscene
