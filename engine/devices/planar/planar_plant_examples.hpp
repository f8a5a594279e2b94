#pragma once
// Plant parameters for the two kinematics families, for tests, benches and as a starting
// point for profiles: the Haplink (serial 2R) and the Haply 2DIY v3 (five-bar), with the
// published geometry and drive constants (../shared/REFERENCE-2D.md) and ESTIMATED masses,
// inertias and friction (nobody publishes them; a profile's values replace these).
#include "engine/base/axes.hpp"
#include "engine/devices/planar/planar_plant.hpp"

namespace hapscene {

struct PlanarPlantExample {
  PlanarPlantParameters parameters;
  Vec2 home_q_rad{};  // a pose well inside the stops, away from singular poses
};

// Haplink: links 87 and 100 mm, joint offsets 0.8727 and -1.4 rad, 72 / 5.5 mm capstans
// (no coupling of the second joint), 48-count motor encoders, 1 / 65.13 N m per motor.
PlanarPlantExample example_haplink_plant();

// Haply 2DIY v3: proximal 70 mm, distal 90 mm, bases 38 mm apart, direct drive, 4880
// counts per revolution, 0.123 N m per motor; joint angles from the x axis.
PlanarPlantExample example_haply2diy_v3_plant();

}  // namespace hapscene
