#pragma once
// The damper: F = -B v, component by component for a vector velocity (the Hapkit lab's
// damper in 1-D, the same law in the plane). Written once for every number of axes; for
// N = 1 it is the lab's formula on doubles, to the bit.
#include <array>

#include "engine/base/axes.hpp"
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"

namespace hapscene {

template <int N>
struct DamperOf {
  static constexpr const char* kType = "damper";
  static constexpr Needs kNeeds{.velocity = true};
  static constexpr bool kUsesProxy = false;
  static constexpr int kAxes = N;
  static constexpr const char* kDescription = "F = -B v";

  double damping_N_s_per_m{};

  static constexpr auto keys() {
    return std::array{KeyOf<DamperOf>{effect_keys::damping(), [](DamperOf& e) { return &e.damping_N_s_per_m; }}};
  }

  Axes<N> force_N(const EffectInputOf<N>& in) const noexcept { return -damping_N_s_per_m * in.v_m_per_s; }
  Axes<N> open_loop_force_N(const EffectInputOf<N>& in) const noexcept { return force_N(in); }

  // Whether it can give a force for some x in [min_m, max_m] (else the scene drops it).
  bool can_act_within(const Axes<N>&, const Axes<N>&) const noexcept { return damping_N_s_per_m != 0.0; }
};

using Damper = DamperOf<1>;

}  // namespace hapscene
