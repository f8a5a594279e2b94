// The safety stage's position hold: no force before a trusted position, a stale one
// ramps force out at the soft-start rate, an implausible one cuts it, and trust
// returning ramps force back in.
#include <doctest/doctest.h>

#include "engine/scene/safety.hpp"

using namespace hapscene;

namespace {
SafetyConfig config_1kHz() {
  SafetyConfig config{.max_force_N = 5.0, .slew_limit_N_per_s = 4000.0, .workspace_min_m = -0.05,
                      .workspace_max_m = 0.045, .soft_start_s = 0.01, .soft_start_threshold_N = 0.5};
  finalise_safety(0.001, &config);  // 10 ticks to ramp
  return config;
}
}  // namespace

TEST_CASE("position hold: nothing before the first trusted position, then the usual soft start") {
  const SafetyConfig config = config_1kHz();
  SafetyState state;
  for (const PositionHold hold : {PositionHold::cut, PositionHold::ramp_out}) {
    state.position_hold = hold;
    for (int i = 0; i < 5; ++i) CHECK(apply_safety(config, 0.0, 3.0, &state) == 0.0);
  }
  CHECK(state.counters.position_hold_ticks == 10);
  CHECK_FALSE(state.started);
  state.position_hold = PositionHold::none;
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 0.0);  // the soft start decides: ramp
  CHECK(apply_safety(config, 0.0, 3.0, &state) == doctest::Approx(0.3));
}

TEST_CASE("position hold: stale ramps out, fresh ramps back in from where it was") {
  const SafetyConfig config = config_1kHz();
  SafetyState state;
  CHECK(apply_safety(config, 0.0, 0.3, &state) == 0.3);  // calm start: no ramp
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 3.0);
  state.position_hold = PositionHold::ramp_out;
  CHECK(apply_safety(config, 0.0, 3.0, &state) == doctest::Approx(2.7));
  CHECK(apply_safety(config, 0.0, 3.0, &state) == doctest::Approx(2.4));
  for (int i = 0; i < 20; ++i) apply_safety(config, 0.0, 3.0, &state);
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 0.0);
  state.position_hold = PositionHold::none;
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 0.0);
  CHECK(apply_safety(config, 0.0, 3.0, &state) == doctest::Approx(0.3));
  for (int i = 0; i < 10; ++i) apply_safety(config, 0.0, 3.0, &state);
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 3.0);
}

TEST_CASE("position hold: an implausible position cuts force (within the slew limit) and restarts the soft start") {
  const SafetyConfig config = config_1kHz();
  SafetyState state;
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 0.0);
  for (int i = 0; i < 20; ++i) apply_safety(config, 0.0, 3.0, &state);
  REQUIRE(apply_safety(config, 0.0, 3.0, &state) == 3.0);
  state.position_hold = PositionHold::cut;
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 0.0);  // 3 N in one step: within 4 N per tick
  CHECK_FALSE(state.started);
  state.position_hold = PositionHold::none;
  CHECK(apply_safety(config, 0.0, 3.0, &state) == 0.0);
  CHECK(apply_safety(config, 0.0, 3.0, &state) == doctest::Approx(0.3));
}
