// `hapscene bench --stress [--noise COUNTS] [--rate HZ]`: the stiffness sweep (largest
// passive, quiet and stable wall at 0.5, 1, 2, 5 and 10 kHz, with the profile's Coulomb
// friction and without, against the textbook bounds) and the damping sweep (largest
// smooth damping per velocity estimator with sensor noise, and each estimator's noise
// and delay) on the simulated Hapkit.
#include <cstdio>

#include "engine/bench/stability_sweep.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"

namespace hapscene {

int bench_stress(Arguments& arguments) {
  const double noise_counts = arguments.take(option::stress_noise).value_or(0.5);
  const double damping_rate_hz = arguments.take(option::stress_rate).value_or(1000.0);
  if (!arguments.positionals().empty()) arguments.fail("--stress takes no environment files");

  const DeviceProfile profile = stress_profile();
  print_out("stiffness sweep: one wall at 10 mm on the simulated %s (m %g kg, b %g N*s/m, Coulomb %g N, and "
            "again with Coulomb 0), harness hand 200 N/m 2 N*s/m 20 g, no sensor noise;\n"
            "passive = the passivity check of press, hold and release passes; stable = no limit cycle (0.2 mm) or "
            "growth in hold and release;\nquiet = stable and at most one sensor count of motion left at the end "
            "(above it a limit cycle persists); log bisection over 200 N/m .. 1 MN/m;\n"
            "bound = min(2b/T, 2fc/D) with that row's friction, the binding one named\n\n",
            profile.name.c_str(), profile.plant.mass_kg, profile.plant.viscous_N_s_per_m, profile.plant.coulomb_N);
  print_out("%8s %5s %13s %13s %13s %14s %8s %14s %10s %14s\n", "rate_Hz", "fc_N", "passive_N/m", "quiet_N/m",
            "stable_N/m", "bound_N/m", "2b/T", "2(b+b_hand)/T", "2fc/D", "passive/(2b/T)");
  for (const StiffnessLimits& l : sweep_wall_stiffness({500.0, 1000.0, 2000.0, 5000.0, 10000.0})) {
    for (const WallLimits* w : {&l.with_coulomb, &l.without_coulomb}) {
      print_out("%8.0f %5.2f %12.0f%s %12.0f%s %12.0f%s %8.0f %-5s %8.0f %14.0f %10.0f %14.2f\n", l.rate_hz,
                w->coulomb_N, w->passive_N_per_m, w->passive_above_range ? "+" : " ", w->quiet_N_per_m,
                w->quiet_above_range ? "+" : " ", w->stable_N_per_m, w->stable_above_range ? "+" : " ",
                w->bound_N_per_m, w->bound_name, l.bound_2b_over_T, l.bound_with_hand,
                w->bound_coulomb_N_per_m,
                w->passive_N_per_m / l.bound_2b_over_T);
    }
  }
  print_out("(+: still passing at the top of the range)\n\n");

  print_out("damping sweep at %g Hz: one damper, sensor noise %g counts (seed 1), hand holding still and "
            "shaking +/-2 mm at 8 Hz;\nsmooth = no jitter (rms second difference of the force <= 0.1 N), "
            "no limit cycle, no growth; log bisection over 0.01 .. 100 N*s/m;\n"
            "noise = rms estimate at rest with that noise rounded to counts; delay and gain on a 5 Hz sine "
            "(delay in ticks of phase lag)\n\n",
            damping_rate_hz, noise_counts);
  print_out("%-12s %14s %14s %12s %8s  %s\n", "estimator", "max_N*s/m", "noise_mm/s", "delay_ticks", "gain",
            "first failure above it");
  const std::vector<EstimatorQuality> qualities = measure_estimators(damping_rate_hz, noise_counts);
  const std::vector<DampingLimit> dampings = sweep_damping(damping_rate_hz, noise_counts);
  for (std::size_t i = 0; i < dampings.size(); ++i) {
    const DampingLimit& l = dampings[i];
    const EstimatorQuality& q = qualities[i];
    print_out("%-12s %13.3f%s %14.2f %12.2f %8.4f  %s\n", l.estimator.c_str(), l.smooth_N_s_per_m,
              l.above_range ? "+" : " ", q.noise_rms_m_per_s * 1e3, q.delay_ticks, q.gain, l.first_failure.c_str());
  }
  return 0;
}

}  // namespace hapscene
