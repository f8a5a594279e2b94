// `hapscene bench --stress [--noise COUNTS] [--rate HZ]`: the stiffness sweep (largest
// passive and largest stable wall at 0.5, 1, 2, 5 and 10 kHz against the textbook
// bounds) and the damping sweep (largest smooth damping per velocity estimator with
// sensor noise) on the simulated Hapkit.
#include <cstdio>

#include "engine/bench/stability_sweep.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/option_definitions.hpp"

namespace hapscene {

int bench_stress(Arguments& arguments) {
  const double noise_counts = arguments.take(option::stress_noise).value_or(0.5);
  const double damping_rate_hz = arguments.take(option::stress_rate).value_or(1000.0);
  if (!arguments.positionals().empty()) arguments.fail("--stress takes no environment files");

  const DeviceProfile profile = stress_profile();
  std::printf("stiffness sweep: one wall at 10 mm on the simulated %s (m %g kg, b %g N*s/m, Coulomb %g N), "
              "harness hand 200 N/m 2 N*s/m 20 g, no sensor noise;\n"
              "passive = the passivity check of press, hold and release passes; stable = no limit cycle or "
              "growth in hold and release; log bisection over 200 N/m .. 1 MN/m\n\n",
              profile.name.c_str(), profile.plant.mass_kg, profile.plant.viscous_N_s_per_m, profile.plant.coulomb_N);
  std::printf("%8s %14s %14s %10s %16s %10s %14s\n", "rate_Hz", "passive_N/m", "stable_N/m", "2b/T", "2(b+b_hand)/T",
              "2fc/D", "passive/(2b/T)");
  for (const StiffnessLimits& l : sweep_wall_stiffness({500.0, 1000.0, 2000.0, 5000.0, 10000.0})) {
    std::printf("%8.0f %13.0f%s %13.0f%s %10.0f %16.0f %10.0f %14.2f\n", l.rate_hz, l.passive_N_per_m,
                l.passive_above_range ? "+" : " ", l.stable_N_per_m, l.stable_above_range ? "+" : " ",
                l.bound_2b_over_T, l.bound_with_hand, l.bound_coulomb, l.passive_N_per_m / l.bound_2b_over_T);
  }
  std::printf("(+: still passing at the top of the range)\n\n");

  std::printf("damping sweep at %g Hz: one damper, sensor noise %g counts (seed 1), hand holding still and "
              "shaking +/-2 mm at 8 Hz;\nsmooth = no jitter (rms second difference of the force <= 0.1 N), "
              "no limit cycle, no growth; log bisection over 0.01 .. 100 N*s/m\n\n",
              damping_rate_hz, noise_counts);
  std::printf("%-12s %14s  %s\n", "estimator", "max_N*s/m", "first failure above it");
  for (const DampingLimit& l : sweep_damping(damping_rate_hz, noise_counts)) {
    std::printf("%-12s %13.3f%s  %s\n", l.estimator.c_str(), l.smooth_N_s_per_m, l.above_range ? "+" : " ",
                l.first_failure.c_str());
  }
  return 0;
}

}  // namespace hapscene
