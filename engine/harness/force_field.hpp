#pragma once
// The scene's force field probed open loop (sum_effects_N at rest, no hand, no device):
// where the stiff regions ("walls") are, for the press scenario and the penetration
// check, and the potential energy the field stores, for the passivity observer.
#include <vector>

#include "engine/harness/open_loop.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// A stretch of the workspace where the field is at least as stiff as the threshold
// (-dF/dx >= K). An edge strictly inside the workspace can be pressed from outside.
struct StiffRegion {
  double low_m{};
  double high_m{};
  bool low_is_edge{};   // free space below low_m: press upward into it
  bool high_is_edge{};  // free space above high_m: press downward into it
  double stiffness_N_per_m{};  // the largest stiffness found in it
};

struct ForceField {
  double min_m{};
  double step_m{};
  std::vector<double> force_N;    // what the scene asks for at rest, per grid point
  std::vector<double> output_N;   // after the static safety rules (clamp, workspace)
  std::vector<double> potential_J;  // -integral of output_N from min_m: energy stored
  std::vector<StiffRegion> regions;   // empty unless the field is static
  // Scripts that keep state or read time have no fixed field: then no stiff regions are
  // inferred and no stored energy is credited (behaviour.note says why).
  ScriptBehaviour behaviour;
  ScriptFaultLog faults;              // script faults met while probing
  // Not empty when the scripts are too slow for the loop (the "pace" message, see
  // pace.hpp): then nothing was probed and the grid is empty.
  std::string too_slow;

  // Linear interpolation of the stored energy at x (clamped to the grid).
  double potential_at_J(double x_m) const noexcept;
  // How deep x is inside a stiff region, measured from its nearest pressable edge (0
  // outside every region or in a region without an edge).
  double penetration_m(double x_m) const noexcept;
};

// The probe's grid step (ForceField::step_m), and at most this many grid points: a
// workspace wider than (kMaxFieldPoints - 1) * kFieldStep_m is refused (InputError
// naming the device profile), so memory and time stay bounded.
inline constexpr double kFieldStep_m = 20e-6;
inline constexpr std::size_t kMaxFieldPoints = 50'001;

// Throws InputError when the scene's workspace needs more than kMaxFieldPoints.
void require_sampleable_workspace(const Scene& scene);

// Probes the scene over its safety workspace every kFieldStep_m, each point from fresh
// script instances (see open_loop.hpp). Scripts too slow for the loop are not probed
// (ForceField::too_slow): thousands of points of them would take hours.
ForceField probe_force_field(const Scene& scene, double stiff_threshold_N_per_m);
// The same, but scripts too slow for the loop throw ScriptsTooSlow (pace.hpp) with the
// failed "pace" check: those of the first calls (check_script_pace) or of the scan.
ForceField scan_force_field(const Scene& scene, double stiff_threshold_N_per_m);

}  // namespace hapscene
