#pragma once
// The Hapkit lab damper: F = -B v.
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"

namespace hapscene {

struct Damper {
  static constexpr const char* kType = "damper";
  static constexpr Needs kNeeds{.velocity = true};
  static constexpr int kAxes = 1;
  static constexpr const char* kDescription = "F = -B v";

  double damping_N_s_per_m{};

  static constexpr auto keys() {
    return std::array{KeyOf<Damper>{effect_keys::damping(), [](Damper& e) { return &e.damping_N_s_per_m; }}};
  }

  double force_N(const EffectInput& in) const noexcept { return -damping_N_s_per_m * in.v_m_per_s; }

  // Whether it can give a force for some x in [min_m, max_m] (else the scene drops it).
  bool can_act_within(double, double) const noexcept { return damping_N_s_per_m != 0.0; }
};

}  // namespace hapscene
