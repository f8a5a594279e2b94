#pragma once
// The spring: F = -K (x - x0), component by component for a vector position (the Hapkit
// lab's spring in 1-D, the same law in the plane). Written once for every number of axes;
// for N = 1 it is the lab's formula on doubles, to the bit.
#include <array>

#include "engine/base/axes.hpp"
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"

namespace hapscene {

template <int N>
struct SpringOf {
  static constexpr const char* kType = "spring";
  static constexpr Needs kNeeds{};
  static constexpr bool kUsesProxy = false;
  static constexpr int kAxes = N;
  static constexpr const char* kDescription = "F = -K (x - center)";

  double stiffness_N_per_m{};
  Axes<N> center_m{};

  static constexpr auto keys() {
    return std::array{
        KeyOf<SpringOf>{effect_keys::stiffness(), [](SpringOf& e) { return &e.stiffness_N_per_m; }},
        KeyOf<SpringOf>{effect_keys::place_or_origin("center", "center_m", KeyForm::vector, "x0"),
                        [](SpringOf& e) { return numbers_of(e.center_m); }},
    };
  }

  Axes<N> force_N(const EffectInputOf<N>& in) const noexcept { return -stiffness_N_per_m * (in.x_m - center_m); }
  Axes<N> open_loop_force_N(const EffectInputOf<N>& in) const noexcept { return force_N(in); }

  // Whether it can give a force for some x in [min_m, max_m] (else the scene drops it).
  bool can_act_within(const Axes<N>&, const Axes<N>&) const noexcept { return stiffness_N_per_m != 0.0; }
};

using Spring = SpringOf<1>;

}  // namespace hapscene
