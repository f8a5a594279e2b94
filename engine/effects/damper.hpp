#pragma once
// The Hapkit lab damper: F = -B v.
#include "engine/effects/effect_input.hpp"

namespace hapscene {

class ObjectReader;

struct Damper {
  static constexpr const char* kType = "damper";
  static constexpr Needs kNeeds{.velocity = true};

  double damping_N_s_per_m{};

  static Damper parse(ObjectReader& reader);

  double force_N(const EffectInput& in) const noexcept { return -damping_N_s_per_m * in.v_m_per_s; }

  // Whether it can give a force for some x in [min_m, max_m] (else the scene drops it).
  bool can_act_within(double, double) const noexcept { return damping_N_s_per_m != 0.0; }
};

}  // namespace hapscene
