#pragma once
// What an effect sees each tick, and what it declares it needs, so that a compiled
// scene computes only what its effects read.

namespace hapscene {

// Handle state for one tick, in SI units and the device's handle frame.
struct EffectInput {
  double x_m{};           // handle position
  double v_m_per_s{};     // estimated velocity; 0 when no effect needs it
  double t_s{};           // time since the run started (a script sees it as s.t only if it declares time)
  double dt_s{};          // tick period
};

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
