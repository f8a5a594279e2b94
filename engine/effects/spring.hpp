#pragma once
// The Hapkit lab spring: F = -K (x - x0).
#include "engine/effects/effect_input.hpp"

namespace hapscene {

class ObjectReader;

struct Spring {
  static constexpr const char* kType = "spring";
  static constexpr Needs kNeeds{};

  double stiffness_N_per_m{};
  double center_m{};

  static Spring parse(ObjectReader& reader);

  double force_N(const EffectInput& in) const noexcept {
    return -stiffness_N_per_m * (in.x_m - center_m);
  }

  // Whether it can give a force for some x in [min_m, max_m] (else the scene drops it).
  bool can_act_within(double, double) const noexcept { return stiffness_N_per_m != 0.0; }
};

}  // namespace hapscene
