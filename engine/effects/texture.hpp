#pragma once
// The Hapkit lab texture: damping fields of width w separated by gaps s, repeating over
// the whole workspace with period p = w + s. The handle is in a field when
// (x - x0) mod p, taken in [0, p), is below w; there F = -B v, elsewhere 0.
// With mirror, |x - x0| takes the place of x - x0: the fields below x0 are the mirror
// image of those above (the lab's solution uses |x|), so the field at x0 is 2 w wide.
// Constant cost whatever the number of fields: one floor per tick.
#include <bit>
#include <cmath>
#include <cstdint>

#include "engine/effects/effect_input.hpp"

namespace hapscene {

class ObjectReader;

struct Texture {
  static constexpr const char* kType = "texture";
  static constexpr Needs kNeeds{.velocity = true};

  double width_m{};
  double spacing_m{};
  double offset_m{};
  double damping_N_s_per_m{};
  double period_m{};  // width_m + spacing_m, computed at load
  bool mirror{};      // fields mirrored about offset_m

  static Texture parse(ObjectReader& reader);

  bool in_field(double x_m) const noexcept {
    const double phase_m = mirror ? std::abs(x_m - offset_m) : x_m - offset_m;
    double within_m = phase_m - period_m * std::floor(phase_m / period_m);
    // Edges written in decimal (x = 0.015 for w = 5 mm) are not exact in binary; positions
    // within a billionth of a period of an edge count as on it, so a field is [x0, x0 + w)
    // as written. (A nanometre is far below any sensor's resolution.)
    // (A multiply, not a branch: see force_N.)
    const double snap_m = 1e-9 * period_m;
    within_m *= static_cast<double>(!(within_m > period_m - snap_m));
    return within_m < width_m - snap_m;
  }

  // Branch-free: whether the handle is in a field changes from tick to tick without a
  // pattern when fields are fine, and a mispredicted branch there cost more than the rest
  // of the effect (time grew 1.66x from 10 to 100 000 fields at a flat instruction
  // count). The field's force is masked by the test's outcome: exactly -B v, or +0.0.
  double force_N(const EffectInput& in) const noexcept {
    const std::uint64_t mask = std::uint64_t{0} - static_cast<std::uint64_t>(in_field(in.x_m));
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(-damping_N_s_per_m * in.v_m_per_s) & mask);
  }

  // Whether it can give a force for some x in [min_m, max_m] (else the scene drops it).
  bool can_act_within(double, double) const noexcept {
    return damping_N_s_per_m != 0.0 && width_m > 0.0;
  }
};

}  // namespace hapscene
