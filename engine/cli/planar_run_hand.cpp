#include "engine/cli/planar_run_hand.hpp"

#include <algorithm>

namespace hapscene {

PlanarHandConfig planar_run_hand(const PlanarScene& scene, PlanarHandMotion motion, const HandConfig& grip,
                                 const Vec2& hold_m) {
  PlanarHandConfig hand;
  hand.motion = motion;
  hand.stiffness_N_per_m = grip.stiffness_N_per_m;
  hand.damping_N_s_per_m = grip.damping_N_s_per_m;
  hand.release_s = grip.release_s;
  hand.hold_m = hold_m;
  const Vec2 low = scene.safety.workspace_min_m;
  const Vec2 high = scene.safety.workspace_max_m;
  const Vec2 middle = (low + high) * 0.5;
  const Vec2 margin = (high - low) * 0.1;
  hand.sweep_min_m = low + margin;
  hand.sweep_max_m = high - margin;
  hand.line_from_m = Vec2{{low[0] + margin[0], middle[1]}};
  hand.line_to_m = Vec2{{high[0] - margin[0], middle[1]}};
  hand.line_back_and_forth = true;
  hand.circle_center_m = middle;
  hand.circle_radius_m = 0.25 * std::min(high[0] - low[0], high[1] - low[1]);
  return hand;
}

}  // namespace hapscene
