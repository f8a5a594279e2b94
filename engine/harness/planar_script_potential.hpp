#pragma once
// The energy a 2-D scene's scripts store, for validate's passivity observer
// (planar_metrics.cpp): the 2-D counterpart of the 1-D ForceField::potential_J.
//
// Method. The scripts' force is taken open loop, as `probe` and the field grid take it
// (PlanarOpenLoop::scan: fresh instances at rest, t = 0), at the nodes of a grid over the
// device's workspace box, less the built-in effects' open-loop force at the same node
// (so only the scripts' part), a non-finite force as 0 and each force clamped to the
// force limit (as a spring's is in the observer). Each grid edge a -> b gets the work
// w = -(F(a) + F(b)) / 2 . (b - a) (trapezoids); the node potentials U are the least
// squares fit of U(b) - U(a) = w over all edges (the discrete Poisson equation, solved
// by conjugate gradients from the line integral along the bottom row and up each
// column). For a conservative field (F = -grad U) the fit is the potential itself; for
// a field with curl it is the potential of the field's gradient part, so the curl's work
// is not credited and shows as energy created (a whirlpool's push round its centre is
// energy the rendering adds, which is right). Between nodes, U(p) is the blend, with
// bilinear weights, of U at each corner of p's cell plus the line integral from that
// corner to p of the bilinearly interpolated force (Simpson's rule): exact for a force
// linear over the cell.
//
// Grid: 1 mm (the fault scan's step) when the scripts render a fixed field. A script
// that keeps state or reads time has no fixed field: its energy is estimated, as in 1-D,
// from the field fresh instances render at rest (a virtual mass settled where the handle
// is), on a coarser grid of about 1000 nodes (fresh instances can cost a creation each).
// Beyond the workspace the rendered output is cut to zero, which this potential ignores:
// it is the field the scripts render inside the workspace.
#include <cstddef>
#include <string>
#include <vector>

#include "engine/harness/open_loop.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct PlanarScriptPotential {
  Vec2 min_m{};             // the grid's first node (the workspace box's lower left)
  double step_m{};          // spacing of the nodes on both axes
  std::size_t columns{};    // nodes along x
  std::size_t rows{};       // nodes along y
  std::vector<Vec2> force_N;        // the scripts' force at each node (index row * columns + column)
  std::vector<double> potential_J;  // U at each node (0 at the first)
  // |the edges' work the fitted potential does not explain| / |the edges' work|, rms over
  // the edges: 0 for a conservative field, near 1 for a pure whirl.
  double rotational_fraction{};
  ScriptBehaviour behaviour;  // whether the scripts render a fixed field (note: why not)
  std::string not_estimated;  // why there is no potential (the open loop's creation budget refused)

  bool empty() const noexcept { return potential_J.empty(); }
  // U at x (clamped to the grid's box); 0 when empty.
  double at_J(const Vec2& x_m) const noexcept;
};

// The grid step for a scene whose scripts render a fixed field.
inline constexpr double kScriptPotentialStep_m = 1e-3;
// About this many nodes for scripts without a fixed field.
inline constexpr std::size_t kScriptPotentialCoarseNodes = 1000;

// The scripts' potential over the workspace box (empty for a scene without scripts).
PlanarScriptPotential planar_script_potential(const PlanarScene& scene);

// What the passivity check's detail adds for a scene with scripts: "; stored energy of
// the script from its field at rest (...)".
std::string describe_script_potential(const PlanarScene& scene, const PlanarScriptPotential& potential);

}  // namespace hapscene
