#pragma once
// The Hapkit lab wall: a spring that pushes only while the handle is inside the solid
// side. "above": F = -K (x - xw) when x > xw; "below": F = -K (x - xw) when x < xw.
#include "engine/core/effect_input.hpp"

namespace hapscene {

class ObjectReader;

struct Wall {
  static constexpr const char* kType = "wall";
  static constexpr Needs kNeeds{};

  double position_m{};
  double stiffness_N_per_m{};
  bool solid_above{true};  // "solid": "above" (x > xw is inside) or "below"

  static Wall parse(ObjectReader& reader);

  double force_N(const EffectInput& in) const noexcept {
    const double penetration_m = in.x_m - position_m;
    const bool inside = solid_above ? penetration_m > 0.0 : penetration_m < 0.0;
    return inside ? -stiffness_N_per_m * penetration_m : 0.0;
  }
};

}  // namespace hapscene
