// One tick: the sensor pipeline, what a compiled scene skips, and velocity estimators.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/devices/kinematics.hpp"
#include "engine/scene/step.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

namespace {
// The raw reading the board reports for a handle position in the home period.
std::int32_t counts_at(const Scene& scene, double x_m) {
  return static_cast<std::int32_t>(std::lround(position_to_counts(scene.device, x_m)));
}
}  // namespace

TEST_CASE("step: counts in, force and motor command out") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  TickState state = make_tick_state(scene);
  const std::int32_t counts = counts_at(scene, 0.004);
  step(scene, counts, &state);
  CHECK(state.sensor.raw_counts == counts);
  CHECK(state.sensor.unwrapped_counts == counts);
  CHECK(state.x_m == counts_to_position_m(scene.device, counts));
  CHECK(state.effects_force_N == -100.0 * state.x_m);
  CHECK(state.output_N == state.effects_force_N);  // 0.4 N: below the soft-start threshold
  CHECK(state.command.duty == force_to_motor(scene.device, state.output_N).duty);
  CHECK(state.command.direction_high == (state.output_N > 0.0));
  CHECK(state.tick == 1);
}

TEST_CASE("step: a scene with no velocity-dependent effect runs no velocity estimator") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100},
    {"type": "wall", "position": 0.002, "stiffness": 500, "solid": "above"}]})");
  REQUIRE_FALSE(scene.needs.velocity);
  TickState state = make_tick_state(scene);
  for (int i = 0; i < 100; ++i) step(scene, counts_at(scene, 0.0001 * i / 100.0 * 40), &state);
  CHECK_FALSE(state.velocity_state.started);
  CHECK(state.v_m_per_s == 0.0);

  const Scene damped = scene_from(R"({"effects": [{"type": "damper", "damping": 1}]})");
  REQUIRE(damped.needs.velocity);
  TickState damped_state = make_tick_state(damped);
  step(damped, counts_at(damped, 0.0), &damped_state);
  step(damped, counts_at(damped, 0.001), &damped_state);
  CHECK(damped_state.velocity_state.started);
  CHECK(damped_state.v_m_per_s > 0.5);
}

TEST_CASE("step: the sensor pipeline follows the handle across sensor periods") {
  const Scene scene = scene_from(R"({"effects": []})");
  TickState state = make_tick_state(scene);
  const DeviceProfile& p = scene.device;
  // Sweep 0 -> +45 mm -> -50 mm in 20 um steps: several flips each way.
  double x_m = 0.0;
  const auto feed = [&](double target_m, double step_m) {
    while ((step_m > 0) ? x_m < target_m : x_m > target_m) {
      x_m += step_m;
      const auto unwrapped = static_cast<std::int64_t>(std::lround(position_to_counts(p, x_m)));
      std::int64_t within = (unwrapped - p.sensor.min_counts) % p.sensor.span_counts;
      if (within < 0) within += p.sensor.span_counts;
      step(scene, static_cast<std::int32_t>(p.sensor.min_counts + within), &state);
      REQUIRE(std::abs(state.x_m - x_m) < 7e-6);  // within half a count
    }
  };
  feed(0.045, 20e-6);
  feed(-0.05, -20e-6);
  CHECK(state.sensor.flip_counter.flips != 0);
}

TEST_CASE("velocity: estimators on a constant-velocity ramp") {
  const double period_s = 0.001;
  const double v_true = 0.05;
  for (const VelocityEstimatorKind kind :
       {VelocityEstimatorKind::difference, VelocityEstimatorKind::hapkit2019,
        VelocityEstimatorKind::hapkit2013, VelocityEstimatorKind::lowpass}) {
    CAPTURE(static_cast<int>(kind));
    VelocityEstimatorConfig config{.kind = kind, .cutoff_Hz = 50.0,
                                   .lowpass_alpha = lowpass_alpha_for(50.0, period_s)};
    VelocityState state;
    CHECK(estimate_velocity(config, 1.0 / period_s, 0.0, &state) == 0.0);  // first sample
    double v = 0.0;
    for (int i = 1; i <= 500; ++i) v = estimate_velocity(config, 1.0 / period_s, v_true * period_s * i, &state);
    CHECK(v == doctest::Approx(v_true).epsilon(1e-6));
  }
}

TEST_CASE("velocity: hapkit2019 is the reference sketch's 0.9 new + 0.1 previous raw difference") {
  VelocityEstimatorConfig config;  // default
  REQUIRE(config.kind == VelocityEstimatorKind::hapkit2019);
  VelocityState state;
  estimate_velocity(config, 1000.0, 0.0, &state);
  CHECK(estimate_velocity(config, 1000.0, 0.001, &state) == doctest::Approx(0.9 * 1.0));
  // The handle stops: 0.1 of the previous raw difference (1 m/s), not of the previous
  // estimate (0.9 m/s).
  CHECK(estimate_velocity(config, 1000.0, 0.001, &state) == doctest::Approx(0.1 * 1.0));
  CHECK(estimate_velocity(config, 1000.0, 0.001, &state) == 0.0);  // a finite response: two ticks
}

TEST_CASE("environment: the velocity block selects the estimator") {
  const Scene scene = scene_from(R"({"velocity": {"estimator": "lowpass", "cutoff": "30 Hz"},
    "effects": [{"type": "damper", "damping": 1}]})");
  CHECK(scene.velocity.kind == VelocityEstimatorKind::lowpass);
  CHECK(scene.velocity.lowpass_alpha == doctest::Approx(lowpass_alpha_for(30.0, 0.001)));
  CHECK(test::load_error(R"({"velocity": {"estimator": "kalman"}, "effects": []})") ==
        "test.json: /velocity/estimator: \"kalman\" is not one of \"hapkit2019\", \"hapkit2013\", "
        "\"difference\", \"lowpass\"");
}

TEST_CASE("step: a spring written in Lua that declares no velocity runs no estimator either") {
  const Scene scene = scene_from(R"({"effects": [{"type": "script", "file": "../scripts/spring.lua"}]})");
  REQUIRE_FALSE(scene.needs.velocity);
  TickState state = make_tick_state(scene);
  for (int i = 0; i < 100; ++i) step(scene, counts_at(scene, 0.00004 * i), &state);
  CHECK_FALSE(state.velocity_state.started);
  CHECK(state.v_m_per_s == 0.0);
}

TEST_CASE("step: one script and ten built-ins make exactly one Lua call per tick") {
  // The script counts its own calls and returns the count in uN; the built-ins are placed
  // so that they push nothing at x = 0 (springs of zero stiffness, walls far away, v = 0).
  const Scene scene = scene_from(R"({"effects": [
    {"type": "script", "source": "local n = 0\nfunction force(s) n = n + 1 return n * 1e-6 end"},
    {"type": "spring", "stiffness": 0}, {"type": "spring", "stiffness": 0},
    {"type": "damper", "damping": 0.1}, {"type": "damper", "damping": 0.1},
    {"type": "texture", "width": 0.005, "damping": 0.1}, {"type": "texture", "width": 0.004, "damping": 0.1},
    {"type": "wall", "position": 0.02, "stiffness": 100, "solid": "above"},
    {"type": "wall", "position": -0.02, "stiffness": 100, "solid": "below"},
    {"type": "wall", "position": 0.03, "stiffness": 100, "solid": "above"},
    {"type": "wall", "position": -0.03, "stiffness": 100, "solid": "below"}]})");
  REQUIRE(scene.effects.size() == 11);
  TickState state = make_tick_state(scene);
  const std::int32_t at_rest = counts_at(scene, 0.0);
  for (int i = 0; i < 1000; ++i) step(scene, at_rest, &state);
  CHECK(state.script_calls == 1000);                                       // the engine's count
  CHECK(state.effects_force_N == doctest::Approx(1000 * 1e-6).epsilon(1e-9));  // the script's own
}

TEST_CASE("step: disabled effects are not in the compiled scene at all") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100},
    {"type": "damper", "damping": 1, "enabled": false},
    {"type": "script", "source": "function force(s) return 0 end", "enabled": false}]})");
  CHECK(scene.effects.size() == 1);
  CHECK(scene.script_count == 0);
  CHECK_FALSE(scene.needs.velocity);
}

TEST_CASE("step: effects that cannot act inside the workspace are listed but never computed") {
  const Scene plain = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  const double max_m = plain.safety.workspace_max_m;
  const double min_m = plain.safety.workspace_min_m;
  // Walls whose solid side lies beyond the workspace, and effects with zero gain.
  const Scene padded = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100},
    {"type": "wall", "position": )" + std::to_string(max_m) + R"(, "stiffness": 1000, "solid": "above"},
    {"type": "wall", "position": )" + std::to_string(min_m - 0.1) + R"(, "stiffness": 1000, "solid": "below"},
    {"type": "damper", "damping": 0}, {"type": "texture", "width": 0.005, "damping": 0},
    {"type": "spring", "stiffness": 0}, {"type": "wall", "position": 0, "stiffness": 0, "solid": "above"}]})");
  CHECK(padded.effects.size() == 7);  // as written, for reports and tools
  CHECK(padded.bank.group<Spring>().size() == 1);
  CHECK(padded.bank.group<Wall>().empty());
  CHECK(padded.bank.group<Damper>().empty());
  CHECK(padded.bank.group<Texture>().empty());
  CHECK_FALSE(padded.needs.velocity);  // the zero-gain damper and texture start no estimator

  // The same ticks as the spring alone, to the bit, across the whole workspace and beyond.
  TickState a = make_tick_state(plain);
  TickState b = make_tick_state(padded);
  for (int i = 0; i <= 2000; ++i) {
    const double x_m = min_m - 0.01 + (max_m - min_m + 0.02) * i / 2000.0;
    step(plain, counts_at(plain, x_m), &a);
    step(padded, counts_at(padded, x_m), &b);
    REQUIRE(b.output_N == a.output_N);
    REQUIRE(b.command.duty == a.command.duty);
  }

  // A wall whose solid side reaches into the workspace, however little, is kept.
  const Scene edge = scene_from(R"({"effects": [{"type": "wall", "position": )" +
                                std::to_string(max_m - 0.001) + R"(, "stiffness": 1000, "solid": "above"}]})");
  CHECK(edge.bank.group<Wall>().size() == 1);
}
