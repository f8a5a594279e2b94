#pragma once
// The Hapkit lab spring: F = -K (x - x0).
#include "engine/core/effect_input.hpp"

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
};

}  // namespace hapscene
