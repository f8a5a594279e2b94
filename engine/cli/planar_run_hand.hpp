#pragma once
// The simulated hand of `hapscene run` on a 2-DOF (planar) scene, from plain values: the
// CLI (run_planar.cpp) and the Python module (python/) build it here, so both drive the
// same path.
#include "engine/devices/hapkit_plant.hpp"
#include "engine/devices/planar/planar_hand.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// The hand over the scene's workspace box: a sweep covers the middle 80 % of it; a line
// crosses it at mid-height, back and forth; a circle of a quarter of its smaller side
// turns round its middle. It holds or releases at `hold_m`. Grip stiffness, damping and
// release time come from `grip` (the 1-DOF hand's settings, as `run` reads them).
PlanarHandConfig planar_run_hand(const PlanarScene& scene, PlanarHandMotion motion, const HandConfig& grip,
                                 const Vec2& hold_m);

}  // namespace hapscene
