#include "engine/harness/planar_open_loop.hpp"

#include <cmath>

#include "engine/scene/safety.hpp"

namespace hapscene {

std::vector<Vec2> planar_workspace_grid(const PlanarScene& scene, double step_m) {
  const Vec2& low = scene.safety.workspace_min_m;
  const Vec2& high = scene.safety.workspace_max_m;
  const auto count = [&](int axis) {
    return static_cast<std::size_t>(std::floor((high[axis] - low[axis]) / step_m + 1e-9)) + 1;
  };
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < count(0); ++i) {
    for (std::size_t j = 0; j < count(1); ++j) {
      const Vec2 p{{low[0] + static_cast<double>(i) * step_m, low[1] + static_cast<double>(j) * step_m}};
      if (within_workspace(scene.safety, p)) points.push_back(p);
    }
  }
  return points;
}

}  // namespace hapscene
