#pragma once
// The Hapkit lab spring: F = -K (x - x0).
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"

namespace hapscene {

struct Spring {
  static constexpr const char* kType = "spring";
  static constexpr Needs kNeeds{};
  static constexpr int kAxes = 1;
  static constexpr const char* kDescription = "F = -K (x - center)";

  double stiffness_N_per_m{};
  double center_m{};

  static constexpr auto keys() {
    return std::array{
        KeyOf<Spring>{effect_keys::stiffness(), [](Spring& e) { return &e.stiffness_N_per_m; }},
        KeyOf<Spring>{effect_keys::place_or_origin("center", "center_m", KeyForm::number, "x0"),
                      [](Spring& e) { return &e.center_m; }},
    };
  }

  double force_N(const EffectInput& in) const noexcept {
    return -stiffness_N_per_m * (in.x_m - center_m);
  }

  // Whether it can give a force for some x in [min_m, max_m] (else the scene drops it).
  bool can_act_within(double, double) const noexcept { return stiffness_N_per_m != 0.0; }
};

}  // namespace hapscene
