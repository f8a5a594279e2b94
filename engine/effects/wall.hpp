#pragma once
// The Hapkit lab wall: a spring that pushes only while the handle is inside the solid
// side. "above": F = -K (x - xw) when x > xw; "below": F = -K (x - xw) when x < xw.
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"

namespace hapscene {

struct Wall {
  static constexpr const char* kType = "wall";
  static constexpr Needs kNeeds{};
  static constexpr int kAxes = 1;
  static constexpr const char* kDescription = "F = -K (x - position) on its solid side";

  double position_m{};
  double stiffness_N_per_m{};
  bool solid_above{true};  // "solid": "above" (x > xw is inside) or "below"

  static constexpr auto keys() {
    return std::array{
        KeyOf<Wall>{effect_keys::place("position", "position_m", KeyForm::number, "xw"),
                    [](Wall& e) { return &e.position_m; }},
        KeyOf<Wall>{effect_keys::stiffness(), [](Wall& e) { return &e.stiffness_N_per_m; }},
        KeyOf<Wall>{effect_keys::solid("above", "below", "solid_above"), nullptr, [](Wall& e) { return &e.solid_above; }},
    };
  }

  double force_N(const EffectInput& in) const noexcept {
    const double penetration_m = in.x_m - position_m;
    const bool inside = solid_above ? penetration_m > 0.0 : penetration_m < 0.0;
    return inside ? -stiffness_N_per_m * penetration_m : 0.0;
  }

  // Whether it can give a force for some x in [min_m, max_m]: not when its solid side
  // lies wholly outside (the safety stage renders nothing there anyway).
  bool can_act_within(double min_m, double max_m) const noexcept {
    return stiffness_N_per_m != 0.0 && (solid_above ? position_m < max_m : position_m > min_m);
  }
};

}  // namespace hapscene
