#pragma once
// The 2-D penalty fields: spring, damper and texture. They need no proxy: each force is
// a function of the handle state alone, the same in closed and open loop.
//   spring:  F = -K (x - c), component by component: fx = -K (x - cx), fy = -K (y - cy)
//   damper:  F = -B v:  fx = -B vx, fy = -B vy
//   texture: bands perpendicular to the unit direction u (the direction as written,
//            divided by its length sqrt(dx dx + dy dy)): the handle is in a band when
//            s = x ux + y uy (in that order) has (s - o) mod (w + s) below w, with the
//            1-D texture's rule for edges (engine/effects/texture.hpp: positions within
//            a billionth of a period of an edge count as on it); there F = -B v, else 0.
#include "engine/base/axes.hpp"
#include "engine/effects/damper.hpp"
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/effects/spring.hpp"
#include "engine/effects/texture.hpp"

namespace hapscene {

// The spring and the damper are the same law in every N (engine/effects/spring.hpp,
// engine/effects/damper.hpp).
using PlanarSpring = SpringOf<2>;
using PlanarDamper = DamperOf<2>;

struct PlanarTexture {
  static constexpr const char* kType = "texture";
  static constexpr Needs kNeeds{.velocity = true};
  static constexpr bool kUsesProxy = false;
  static constexpr int kAxes = 2;
  static constexpr const char* kDescription = "damping bands";

  Texture bands;      // width, spacing, offset, damping and period along the direction
  Vec2 direction{};   // unit vector

  static constexpr auto keys() {
    return std::array{
        KeyOf<PlanarTexture>{effect_keys::band_width(), [](PlanarTexture& e) { return &e.bands.width_m; }},
        KeyOf<PlanarTexture>{effect_keys::damping("B within a field"),
                             [](PlanarTexture& e) { return &e.bands.damping_N_s_per_m; }},
        KeyOf<PlanarTexture>{effect_keys::band_spacing(), [](PlanarTexture& e) { return &e.bands.spacing_m; }},
        KeyOf<PlanarTexture>{effect_keys::band_offset(), [](PlanarTexture& e) { return &e.bands.offset_m; }},
        KeyOf<PlanarTexture>{effect_keys::direction("direction", "the direction across the bands"),
                             [](PlanarTexture& e) { return e.direction.value; }},
    };
  }
  static void finish_parse(ObjectReader&, PlanarTexture& texture) noexcept { texture.bands.derive_period(); }

  bool in_band(const Vec2& x_m) const noexcept {
    return bands.in_field(x_m[0] * direction[0] + x_m[1] * direction[1]);
  }
  Vec2 force_N(const PlanarInput& in) const noexcept {
    if (!in_band(in.x_m)) return Vec2{};
    return Vec2{{-bands.damping_N_s_per_m * in.v_m_per_s[0], -bands.damping_N_s_per_m * in.v_m_per_s[1]}};
  }
  Vec2 open_loop_force_N(const PlanarInput& in) const noexcept { return force_N(in); }
  bool can_act_within(const Vec2&, const Vec2&) const noexcept {
    return bands.damping_N_s_per_m != 0.0 && bands.width_m > 0.0;
  }
};

}  // namespace hapscene
