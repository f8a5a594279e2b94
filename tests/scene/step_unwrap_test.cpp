// The host's sensor stage keeps the handle's position when a sample lands on the way
// across the sensor's wrap (the shared FlipCounter, as in the firmware).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "engine/devices/kinematics.hpp"
#include "engine/scene/step.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

TEST_CASE("step: a sample caught in transit across the wrap costs no sensor period") {
  const Scene scene = scene_from(R"({"effects": []})");
  TickState state = make_tick_state(scene);
  const DeviceProfile& p = scene.device;
  const auto raw_at = [&](double x_m) {
    const auto unwrapped = static_cast<std::int64_t>(std::lround(position_to_counts(p, x_m)));
    std::int64_t within = (unwrapped - p.sensor.min_counts) % p.sensor.span_counts;
    if (within < 0) within += p.sensor.span_counts;
    return static_cast<std::int32_t>(p.sensor.min_counts + within);
  };
  // Sweep 0 -> +45 mm -> -50 mm in 0.5 mm steps; at every wrap one sample lands halfway
  // through the sensor's swing.
  double x_m = 0.0;
  int transits = 0;
  const auto feed = [&](double target_m, double step_m) {
    while ((step_m > 0) ? x_m < target_m : x_m > target_m) {
      const std::int32_t before = raw_at(x_m);
      x_m += step_m;
      const std::int32_t after = raw_at(x_m);
      if (std::abs(after - before) > p.sensor.flip_threshold_counts) {
        step(scene, (before + after) / 2, &state);
        ++transits;
      }
      step(scene, after, &state);
      REQUIRE(std::abs(state.x_m - x_m) < 7e-6);  // within half a count
    }
  };
  feed(0.045, 0.5e-3);
  feed(-0.05, -0.5e-3);
  CHECK(transits >= 4);
}
