// The safety stage: each rule on its own, in order, and counted.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "engine/scene/safety.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {
SafetyConfig config_1kHz() {
  SafetyConfig config{.max_force_N = 5.0, .slew_limit_N_per_s = 4000.0, .workspace_min_m = -0.05,
                      .workspace_max_m = 0.045, .soft_start_s = 0.5, .soft_start_threshold_N = 0.5};
  finalise_safety(0.001, &config);
  return config;
}
}  // namespace

TEST_CASE("safety: derived per-tick limits") {
  const SafetyConfig config = config_1kHz();
  CHECK(config.max_step_N == doctest::Approx(4.0));
  CHECK(config.ramp_step_per_tick == doctest::Approx(0.002));
}

TEST_CASE("safety: non-finite force is zero and counted") {
  const SafetyConfig config = config_1kHz();
  SafetyState state;
  CHECK(apply_safety(config, 0.0, std::numeric_limits<double>::quiet_NaN(), &state) == 0.0);
  CHECK(apply_safety(config, 0.0, std::numeric_limits<double>::infinity(), &state) == 0.0);
  CHECK(apply_safety(config, 0.0, -std::numeric_limits<double>::infinity(), &state) == 0.0);
  CHECK(state.counters.nonfinite_faults == 3);
}

TEST_CASE("safety: clamp to the force limit, keeping the sign") {
  const SafetyConfig config = config_1kHz();
  SafetyCounters counters;
  CHECK(apply_static_safety(config, 0.0, 4.9, &counters) == 4.9);
  CHECK(apply_static_safety(config, 0.0, 12.0, &counters) == 5.0);
  CHECK(apply_static_safety(config, 0.0, -1e300, &counters) == -5.0);
  CHECK(counters.clamped_ticks == 2);
}

TEST_CASE("safety: no force outside the workspace") {
  const SafetyConfig config = config_1kHz();
  SafetyCounters counters;
  CHECK(apply_static_safety(config, 0.045, 1.0, &counters) == 1.0);
  CHECK(apply_static_safety(config, 0.0451, 1.0, &counters) == 0.0);
  CHECK(apply_static_safety(config, -0.06, -3.0, &counters) == 0.0);
  CHECK(apply_static_safety(config, std::nan(""), 1.0, &counters) == 0.0);
  CHECK(counters.outside_workspace_ticks == 3);
}

TEST_CASE("safety: the slew limit bounds the change per tick") {
  const SafetyConfig config = config_1kHz();  // 4 N per tick
  SafetyState state;
  CHECK(apply_safety(config, 0.0, 0.2, &state) == 0.2);  // below the soft-start threshold
  CHECK(apply_safety(config, 0.0, 5.0, &state) == doctest::Approx(4.2));
  CHECK(apply_safety(config, 0.0, 5.0, &state) == 5.0);
  CHECK(apply_safety(config, 0.0, -5.0, &state) == doctest::Approx(1.0));
  CHECK(apply_safety(config, 0.0, -5.0, &state) == doctest::Approx(-3.0));
  CHECK(apply_safety(config, 0.0, -5.0, &state) == -5.0);
  CHECK(state.counters.slew_limited_ticks == 3);
}

TEST_CASE("safety: soft start ramps force in when a run starts inside a force field") {
  const SafetyConfig config = config_1kHz();  // 0.5 s ramp: 0.002 per tick
  SafetyState state;
  CHECK(apply_safety(config, 0.02, -3.0, &state) == 0.0);
  CHECK(apply_safety(config, 0.02, -3.0, &state) == doctest::Approx(-3.0 * 0.002));
  for (int tick = 2; tick < 500; ++tick) apply_safety(config, 0.02, -3.0, &state);
  CHECK(apply_safety(config, 0.02, -3.0, &state) == -3.0);
  CHECK(state.counters.soft_start_ticks == 500);
  CHECK(state.counters.slew_limited_ticks == 0);

  // Starting where the scene asks for little force: no ramp.
  SafetyState calm;
  CHECK(apply_safety(config, 0.0, 0.3, &calm) == 0.3);
  CHECK(calm.counters.soft_start_ticks == 0);

  // After a scene swap the next tick decides again.
  restart_soft_start(&calm);
  CHECK(apply_safety(config, 0.0, 2.0, &calm) == 0.0);
}

}  // namespace HAPSCENE_TEST_FILE
