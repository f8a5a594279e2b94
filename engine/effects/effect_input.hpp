#pragma once
// What an effect sees each tick, and what it declares it needs, so that a compiled
// scene computes only what its effects read.
#include "engine/base/axes.hpp"

namespace hapscene {

// Handle state for one tick of a scene with N axes, in SI units and the device's task
// frame (docs/explanation/n-axis.md). For N = 1 the vectors are doubles.
template <int N>
struct EffectInputOf {
  Axes<N> x_m{};          // handle position
  Axes<N> v_m_per_s{};    // estimated velocity; 0 when no effect needs it
  double t_s{};           // time since the run started (a script sees it as s.t only if it declares time)
  double dt_s{};          // tick period
};

using EffectInput = EffectInputOf<1>;
using PlanarInput = EffectInputOf<2>;  // a 2-DOF device's: x and y

// Inputs an effect reads besides position.
struct Needs {
  bool velocity{};
  bool time{};

  Needs& operator|=(const Needs& other) {
    velocity = velocity || other.velocity;
    time = time || other.time;
    return *this;
  }
};

}  // namespace hapscene
