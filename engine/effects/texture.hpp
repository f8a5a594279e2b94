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
#include "engine/effects/effect_keys.hpp"

namespace hapscene {

struct Texture {
  static constexpr const char* kType = "texture";
  static constexpr Needs kNeeds{.velocity = true};
  static constexpr int kAxes = 1;
  static constexpr const char* kDescription = "damping bands";

  double width_m{};
  double spacing_m{};
  double offset_m{};
  double damping_N_s_per_m{};
  double period_m{};  // width_m + spacing_m (derive_period)
  bool mirror{};      // fields mirrored about offset_m
  // Derived (derive_period; for a Texture built field by field, these initialisers):
  // 1 / period_m, so the tick multiplies instead of dividing (a division's latency was
  // most of the effect's time). It can move floor() by one where the phase lies within an
  // ulp or two of an edge; within_m is then about 0 or about period_m, both of which the
  // snap (in_field) reads as that edge, as before.
  double periods_per_m = 1.0 / period_m;
  // Edges written in decimal (x = 0.015 for w = 5 mm) are not exact in binary; positions
  // within a billionth of a period of an edge count as on it, so a field is [x0, x0 + w)
  // as written. (A nanometre is far below any sensor's resolution.) These are the field's
  // end and the period's end, each moved back by that billionth.
  double field_end_m = width_m - 1e-9 * period_m;
  double period_end_m = period_m - 1e-9 * period_m;

  // Sets the period and what derives from it, from width_m and spacing_m (at load).
  void derive_period() noexcept {
    period_m = width_m + spacing_m;
    periods_per_m = 1.0 / period_m;
    field_end_m = width_m - 1e-9 * period_m;
    period_end_m = period_m - 1e-9 * period_m;
  }

  static constexpr auto keys() {
    return std::array{
        KeyOf<Texture>{effect_keys::band_width(), [](Texture& e) { return &e.width_m; }},
        KeyOf<Texture>{effect_keys::damping("B within a field"), [](Texture& e) { return &e.damping_N_s_per_m; }},
        KeyOf<Texture>{effect_keys::band_spacing(), [](Texture& e) { return &e.spacing_m; }},
        KeyOf<Texture>{effect_keys::band_offset(), [](Texture& e) { return &e.offset_m; }},
        KeyOf<Texture>{key("mirror", KeyForm::flag).or_default(0.0).as("mirror")
                           .says("the fields below the offset mirror those above"),
                       nullptr, [](Texture& e) { return &e.mirror; }},
    };
  }
  static void finish_parse(ObjectReader&, Texture& texture) noexcept { texture.derive_period(); }

  bool in_field(double x_m) const noexcept {
    const double phase_m = mirror ? std::abs(x_m - offset_m) : x_m - offset_m;
    const double within_m = phase_m - period_m * std::floor(phase_m * periods_per_m);
    // In the field, or within the snap of the period's end: that is the next field's
    // start edge (0), in the field when the field is wider than the snap. (Comparisons
    // combined without a branch: see force_N. A NaN is in no field.)
    return (within_m < field_end_m) | ((within_m > period_end_m) & (field_end_m > 0.0));
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
