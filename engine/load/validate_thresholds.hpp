#pragma once
// What `hapscene validate` judges a scene by. An environment carries its own thresholds
// in its optional "validate" block, which the loader reads beside the scene (Environment,
// environment.hpp) and the harness takes through HarnessOptions::thresholds; the tick
// never reads them. The defaults suit a Hapkit lab environment. A negative value means
// "derive from the scene" (see the comment of each field).
#include <cstdint>

namespace hapscene {

struct ValidateThresholds {
  // Checks, one verdict each per scenario.
  double max_force_N{-1.0};                // < 0: the scene's safety force limit
  double max_time_at_limit_fraction{0.1};  // of the scenario's ticks at the force limit
  double max_slew_N_per_s{-1.0};           // < 0: the scene's slew limit (reaching it fails)
  std::uint64_t max_slip_ticks{0};         // ticks above the profile's slip force or step
  double max_passivity_ratio{1.0};         // energy created / device's own dissipation
  double max_residual_amplitude_m{2e-4};   // oscillation left at the end of a watch window
  double max_amplitude_growth{1.0};        // late / early oscillation amplitude
  double max_penetration_m{0.015};         // into any stiff region the harness found
  double max_force_jitter_N{0.1};          // rms second difference of the commanded force
  double max_tick_compute_s{-1.0};         // p99 of tick compute; < 0: half the period
  std::uint64_t max_script_faults{0};      // script errors plus budget overruns
  // 2-DOF scenes only (the planar "validate" block; a 1-DOF block refuses them).
  std::uint64_t max_pop_through{0};        // crossings of a solid the rendering let through
  std::uint64_t max_singularity_ticks{0};  // ticks force was asked for while the pose was held

  // How the scenarios are built.
  double stiff_threshold_N_per_m{200.0};   // a region at least this stiff is a "wall" to press
  double press_force_N{3.0};               // how hard the hand presses (at its stiffness)
  double release_from_m{0.02};             // release: displacement from the start, then let go
};

}  // namespace hapscene
