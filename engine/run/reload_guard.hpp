#pragma once
// What a hot reload may not do: change the rate, change the device (its profile's
// content, whatever file or name it comes from), or loosen any safety limit of the scene
// in force. Checked by the reload thread before a new version is offered to the loop.
#include <string>

#include "engine/scene/scene.hpp"

namespace hapscene {

// "" when `next` may replace `running`; otherwise one message naming every change that
// is refused ("device profile content changed: limits.max_force_N 6 -> 60; ...").
std::string reload_refusal(const Scene& running, const Scene& next);
// The same for a planar scene: every field of its profile, and its workspace box per axis.
std::string reload_refusal(const PlanarScene& running, const PlanarScene& next);

}  // namespace hapscene
