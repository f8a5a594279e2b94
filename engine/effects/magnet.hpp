#pragma once
// A magnet: a point that pulls the handle in when it comes within a radius, for snapping
// to a target, a detent, or a button's centre. With d = x - c and r its radius:
//   |d| <= r/2:       F = -K d                      (a spring toward c)
//   r/2 < |d| < r:    F = -K (r - |d|) d / |d|      (falling to zero at the rim)
//   |d| >= r:         F = 0
// continuous everywhere (the force peaks at K r / 2 on the circle |d| = r/2), and the
// gradient of a potential, so it stores energy and gives it back like a spring; its
// stiffness is K inside r/2 and -K beyond, so it is judged for stability by K like a
// spring. Written once for every number of axes (Axes<1> is a double: |d| is fabs(d)).
#include <array>
#include <cmath>

#include "engine/base/axes.hpp"
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"

namespace hapscene {

template <int N>
struct MagnetOf {
  static constexpr const char* kType = "magnet";
  static constexpr Needs kNeeds{};
  static constexpr bool kUsesProxy = false;
  static constexpr int kAxes = N;
  static constexpr const char* kDescription =
      "pulls the handle to a point: F = -K d within half the radius, falling to zero at the radius";

  Axes<N> center_m{};
  double radius_m{};
  double stiffness_N_per_m{};

  static constexpr auto keys() {
    return std::array{
        KeyOf<MagnetOf>{effect_keys::place("center", "center_m", KeyForm::vector, "the point it pulls to"),
                        [](MagnetOf& e) { return numbers_of(e.center_m); }},
        KeyOf<MagnetOf>{key("radius", KeyForm::number, Quantity::length_m, ranges::kRadius_m)
                            .needed().slides().as("radius_m").says("where its pull ends"),
                        [](MagnetOf& e) { return &e.radius_m; }},
        KeyOf<MagnetOf>{effect_keys::stiffness("K: the pull's slope near the point"),
                        [](MagnetOf& e) { return &e.stiffness_N_per_m; }},
    };
  }

  Axes<N> force_N(const EffectInputOf<N>& in) const noexcept {
    const Axes<N> d_m = in.x_m - center_m;
    const double distance_m = norm(d_m);
    // Beyond the rim, or a non-finite position: no force.
    if (!(distance_m < radius_m)) return Axes<N>{};
    if (distance_m <= 0.5 * radius_m) return d_m * -stiffness_N_per_m;
    return d_m * (-stiffness_N_per_m * (radius_m - distance_m) / distance_m);
  }
  Axes<N> open_loop_force_N(const EffectInputOf<N>& in) const noexcept { return force_N(in); }

  // The energy it stores with the handle at x (zero at the point, K r^2 / 4 from the rim
  // on): U = K s^2 / 2 for s = |d| <= r/2, K (r s - s^2 / 2 - r^2 / 4) up to the rim. The
  // validators count it beside the springs' when they judge passivity.
  double potential_J(const Axes<N>& x_m) const noexcept {
    const double s = std::fmin(norm(x_m - center_m), radius_m);
    if (s <= 0.5 * radius_m) return 0.5 * stiffness_N_per_m * s * s;
    return stiffness_N_per_m * (radius_m * s - 0.5 * s * s - 0.25 * radius_m * radius_m);
  }

  // Whether its disc (its interval in 1-D) meets the box [min_m, max_m] with a pull.
  bool can_act_within(const Axes<N>& min_m, const Axes<N>& max_m) const noexcept {
    if (stiffness_N_per_m == 0.0) return false;
    double gap_squared_m2 = 0.0;
    for (int i = 0; i < N; ++i) {
      const double c = component(center_m, i);
      const double gap_m = std::fmax(component(min_m, i) - c, 0.0) + std::fmax(c - component(max_m, i), 0.0);
      gap_squared_m2 += gap_m * gap_m;
    }
    return gap_squared_m2 < radius_m * radius_m;
  }
};

}  // namespace hapscene
