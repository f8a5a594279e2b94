// The 2-D virtual hand: its reference paths (exact positions and velocities), and the
// simulated handle following them within a stated error when no force field acts, on both
// kinematics families with their friction on.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/devices/planar/planar_hand.hpp"
#include "engine/devices/planar/planar_plant.hpp"
#include "engine/devices/planar/planar_plant_examples.hpp"

using namespace hapscene;

namespace {

constexpr double kTick_s = 1e-3;

bool near(const Vec2& a, const Vec2& b, double tolerance) { return norm(a - b) <= tolerance; }

// Runs the example plant with the hand and no motor torque; the largest distance between
// the handle and the reference after `settle_s`.
double worst_following_error_m(const PlanarPlantExample& example, const PlanarHandConfig& hand, double duration_s,
                               double settle_s) {
  PlanarSimulationConfig config;
  config.start_q_rad = example.home_q_rad;
  config.hand = hand;
  PlanarPlant plant(example.parameters, config);
  double worst = 0.0;
  const auto ticks = static_cast<int>(duration_s / kTick_s);
  for (int k = 0; k < ticks; ++k) {
    plant.advance(kTick_s);
    if (plant.t_s() >= settle_s) worst = std::max(worst, norm(plant.handle_m() - plant.hand().reference_m(plant.t_s())));
  }
  CHECK(plant.linkage_faults() == 0);
  return worst;
}

Vec2 home_of(const PlanarPlantExample& example) {
  return solve_linkage(example.parameters.linkage, example.home_q_rad).handle_m;
}

}  // namespace

TEST_CASE("planar hand: a line starts where the handle is, travels at its speed and holds at its end") {
  PlanarHandConfig c;
  c.motion = PlanarHandMotion::line;
  c.line_from_m = Vec2{{0.0, 0.1}};
  c.line_to_m = Vec2{{0.03, 0.14}};  // 50 mm
  c.speed_m_per_s = 0.1;
  const PlanarHand hand(c, Vec2{{0.0, 0.09}});  // 10 mm lead-in
  CHECK(hand.reference_m(0.0) == Vec2{{0.0, 0.09}});
  CHECK(near(hand.reference_m(0.05), Vec2{{0.0, 0.095}}, 1e-12));
  CHECK(near(hand.reference_velocity_m_per_s(0.05), Vec2{{0.0, 0.1}}, 1e-12));
  CHECK(near(hand.reference_m(0.1 + 0.25), Vec2{{0.015, 0.12}}, 1e-12));
  CHECK(near(hand.reference_velocity_m_per_s(0.35), Vec2{{0.06, 0.08}}, 1e-12));
  CHECK(near(hand.reference_m(10.0), c.line_to_m, 1e-15));
  CHECK(hand.reference_velocity_m_per_s(10.0) == Vec2{});
  CHECK(hand.gripping(10.0));

  // Back and forth: 0.6 s after the lead-in it is back at the line's start.
  c.line_back_and_forth = true;
  const PlanarHand bouncing(c, Vec2{{0.0, 0.09}});
  CHECK(near(bouncing.reference_m(0.1 + 0.75), Vec2{{0.015, 0.12}}, 1e-12));
  CHECK(near(bouncing.reference_velocity_m_per_s(0.85), Vec2{{-0.06, -0.08}}, 1e-12));
  CHECK(near(bouncing.reference_m(1.1), c.line_from_m, 1e-12));
}

TEST_CASE("planar hand: a circle runs at its speed and radius, in its direction") {
  PlanarHandConfig c;
  c.motion = PlanarHandMotion::circle;
  c.circle_center_m = Vec2{{0.0, 0.1}};
  c.circle_radius_m = 0.02;
  c.speed_m_per_s = 0.04;
  const PlanarHand hand(c, Vec2{{0.02, 0.1}});  // on the circle's start: no lead-in
  for (double t = 0.0; t < 5.0; t += 0.137) {
    CHECK(norm(hand.reference_m(t) - c.circle_center_m) == doctest::Approx(0.02));
    CHECK(norm(hand.reference_velocity_m_per_s(t)) == doctest::Approx(0.04));
  }
  // A quarter turn (31.4 mm) counter-clockwise: the top.
  CHECK(near(hand.reference_m(0.25 * 2 * std::numbers::pi * 0.02 / 0.04), Vec2{{0.0, 0.12}}, 1e-12));
  c.circle_clockwise = true;
  const PlanarHand clockwise(c, Vec2{{0.02, 0.1}});
  CHECK(near(clockwise.reference_m(0.25 * 2 * std::numbers::pi * 0.02 / 0.04), Vec2{{0.0, 0.08}}, 1e-12));
}

TEST_CASE("planar hand: a sweep's raster covers its box") {
  PlanarHandConfig c;
  c.motion = PlanarHandMotion::sweep;
  c.sweep_min_m = Vec2{{-0.02, 0.08}};
  c.sweep_max_m = Vec2{{0.02, 0.11}};
  c.sweep_pitch_m = 0.005;
  c.speed_m_per_s = 0.1;
  const PlanarHand hand(c, Vec2{{-0.02, 0.08}});
  // Sample one pass (7 rows of 40 mm plus 6 steps of 5 mm: 310 mm) finely; every point of
  // a grid over the box is within half a pitch of the path, and the path stays in the box.
  std::vector<Vec2> samples;
  for (double t = 0.0; t <= 3.1; t += 1e-4) samples.push_back(hand.reference_m(t));
  for (const Vec2& p : samples) {
    CHECK(p[0] >= -0.02 - 1e-12);
    CHECK(p[0] <= 0.02 + 1e-12);
    CHECK(p[1] >= 0.08 - 1e-12);
    CHECK(p[1] <= 0.11 + 1e-12);
  }
  for (double x = -0.02; x <= 0.02; x += 0.002) {
    for (double y = 0.08; y <= 0.11; y += 0.001) {
      double nearest = INFINITY;
      for (const Vec2& p : samples) nearest = std::min(nearest, norm(p - Vec2{{x, y}}));
      CHECK(nearest <= 0.0025 + 1e-5);
    }
  }
  // Then it comes back: at 3.1 s it is at the top row's end (7 rows: the last runs
  // rightward), at 6.2 s back at the start.
  CHECK(near(hand.reference_m(3.1), Vec2{{0.02, 0.11}}, 1e-9));
  CHECK(near(hand.reference_m(6.2), Vec2{{-0.02, 0.08}}, 1e-9));
}

TEST_CASE("planar hand: hold, release, shake and timed paths") {
  PlanarHandConfig c;
  c.motion = PlanarHandMotion::release;
  c.hold_m = Vec2{{0.01, 0.1}};
  c.release_s = 0.3;
  const PlanarHand release(c, Vec2{});
  CHECK(release.gripping(0.29));
  CHECK_FALSE(release.gripping(0.3));
  CHECK(release.force_N(0.5, Vec2{}, Vec2{}) == Vec2{});
  CHECK(release.force_N(0.0, Vec2{}, Vec2{}) == c.stiffness_N_per_m * c.hold_m);

  c.motion = PlanarHandMotion::shake;
  c.shake_direction = Vec2{{0.0, 2.0}};  // normalised
  c.shake_amplitude_m = 0.001;
  c.shake_frequency_Hz = 10.0;
  const PlanarHand shake(c, Vec2{});
  CHECK(near(shake.reference_m(0.025), c.hold_m + Vec2{{0.0, 0.001}}, 1e-15));

  c.motion = PlanarHandMotion::path;
  c.path = {{0.0, Vec2{{0.0, 0.1}}, true}, {1.0, Vec2{{0.02, 0.1}}, false}, {2.0, Vec2{{0.02, 0.1}}, true}};
  const PlanarHand path(c, Vec2{});
  CHECK(near(path.reference_m(0.5), Vec2{{0.01, 0.1}}, 1e-15));
  CHECK(near(path.reference_velocity_m_per_s(0.5), Vec2{{0.02, 0.0}}, 1e-15));
  CHECK(path.gripping(0.5));
  CHECK_FALSE(path.gripping(1.5));
  CHECK(path.gripping(3.0));
  CHECK(path.reference_velocity_m_per_s(3.0) == Vec2{});
}

TEST_CASE("planar hand: configurations that describe no path are refused, naming the field") {
  PlanarHandConfig c;
  c.motion = PlanarHandMotion::circle;
  c.circle_radius_m = 0.0;
  CHECK_THROWS_WITH_AS(PlanarHand(c, Vec2{}), doctest::Contains("circle radius"), InputError);
  c = PlanarHandConfig{};
  c.motion = PlanarHandMotion::sweep;
  c.sweep_min_m = Vec2{{0.0, 0.0}};
  c.sweep_max_m = Vec2{{0.0, 0.01}};
  CHECK_THROWS_WITH_AS(PlanarHand(c, Vec2{}), doctest::Contains("sweep box"), InputError);
  c = PlanarHandConfig{};
  c.motion = PlanarHandMotion::line;
  c.speed_m_per_s = -1.0;
  CHECK_THROWS_WITH_AS(PlanarHand(c, Vec2{}), doctest::Contains("speed"), InputError);
  c = PlanarHandConfig{};
  c.motion = PlanarHandMotion::path;
  c.path = {{1.0, Vec2{}, true}, {1.0, Vec2{}, true}};
  CHECK_THROWS_WITH_AS(PlanarHand(c, Vec2{}), doctest::Contains("times must increase"), InputError);
  c = PlanarHandConfig{};
  c.motion = PlanarHandMotion::hold;
  c.hold_m = Vec2{{NAN, 0.0}};
  CHECK_THROWS_WITH_AS(PlanarHand(c, Vec2{}), doctest::Contains("hold"), InputError);
}

TEST_CASE("planar hand: the simulated handle follows a hold, a line and a circle within 1 mm (no force field)") {
  // Hand 300 N/m, 3 N s/m, the examples' friction on: the hand's spring has to overcome the
  // joints' Coulomb friction and the handle's inertia. After the first 0.3 s the handle is
  // within 1 mm of the reference everywhere on the path (measured: hold 0.25 / 0.05 mm,
  // line 0.69 / 0.76 mm, circle 0.67 / 0.52 mm for the Haplink / 2DIY examples).
  for (const PlanarPlantExample& example : {example_haplink_plant(), example_haply2diy_v3_plant()}) {
    const Vec2 home = home_of(example);
    PlanarHandConfig hand;
    hand.stiffness_N_per_m = 300.0;
    hand.damping_N_s_per_m = 3.0;

    hand.motion = PlanarHandMotion::hold;
    hand.hold_m = home + Vec2{{0.005, 0.005}};
    const double hold = worst_following_error_m(example, hand, 1.0, 0.3);

    hand.motion = PlanarHandMotion::line;
    hand.line_from_m = home + Vec2{{-0.015, -0.01}};
    hand.line_to_m = home + Vec2{{0.015, 0.01}};
    hand.line_back_and_forth = true;
    hand.speed_m_per_s = 0.05;
    const double line = worst_following_error_m(example, hand, 3.0, 0.3);

    hand.motion = PlanarHandMotion::circle;
    hand.circle_center_m = home;
    hand.circle_radius_m = 0.015;
    hand.speed_m_per_s = 0.05;
    const double circle = worst_following_error_m(example, hand, 3.0, 0.3);
    MESSAGE(std::string(example.parameters.linkage.family == LinkageFamily::serial_2r ? "serial 2R" : "five-bar"),
            ": worst following error hold ", hold * 1e3, " mm, line ", line * 1e3, " mm, circle ", circle * 1e3, " mm");
    CHECK(hold < 1e-3);
    CHECK(line < 1e-3);
    CHECK(circle < 1e-3);
  }
}

TEST_CASE("planar hand: after a release the hand's force is gone and the handle coasts to rest") {
  const PlanarPlantExample example = example_haply2diy_v3_plant();
  PlanarSimulationConfig config;
  config.start_q_rad = example.home_q_rad;
  config.hand.motion = PlanarHandMotion::release;
  config.hand.hold_m = home_of(example) + Vec2{{0.01, 0.0}};
  config.hand.release_s = 0.5;
  PlanarPlant plant(example.parameters, config);
  for (int k = 0; k < 500; ++k) plant.advance(kTick_s);
  CHECK(norm(plant.handle_m() - config.hand.hold_m) < 1e-3);  // held displaced
  for (int k = 0; k < 1500; ++k) plant.advance(kTick_s);
  CHECK(plant.hand_force_N() == Vec2{});
  CHECK(plant.q_dot_rad_per_s() == Vec2{});  // friction stopped it
}

TEST_CASE("planar plant: the hand's mass adds to the handle while it grips") {
  const PlanarPlantExample example = example_haply2diy_v3_plant();
  const PlanarMassModel model(example.parameters, example.home_q_rad);
  PlanarDynamics bare, held;
  REQUIRE(model.evaluate(example.home_q_rad, Vec2{}, 0.0, &bare));
  REQUIRE(model.evaluate(example.home_q_rad, Vec2{}, 0.1, &held));
  const Jacobian2& j = bare.pose.jacobian;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      const double added = 0.1 * (j.m[0][a] * j.m[0][b] + j.m[1][a] * j.m[1][b]);
      CHECK(held.mass.m[a][b] - bare.mass.m[a][b] == doctest::Approx(added));
    }
  }
}

TEST_CASE("planar hand: the path's corners are reported, and the plant's steps end on them") {
  PlanarHandConfig c;
  c.motion = PlanarHandMotion::line;
  c.line_from_m = Vec2{{0.0, 0.1}};
  c.line_to_m = Vec2{{0.03, 0.14}};  // 50 mm
  c.line_back_and_forth = true;
  c.speed_m_per_s = 0.1;
  const PlanarHand line(c, Vec2{{0.0, 0.09}});  // lead-in 10 mm: corner at 0.1 s
  CHECK(line.next_break_s(0.0) == doctest::Approx(0.1));
  CHECK(line.next_break_s(0.1) == doctest::Approx(0.6));
  CHECK(line.next_break_s(0.7) == doctest::Approx(1.1));
  CHECK(line.next_break_s(1.2) == doctest::Approx(1.6));

  // A circle entered from its centre: the reference velocity turns 90 degrees at 0.15 s,
  // between two ticks' substeps only by rounding. With the step ending there, RK4 keeps its
  // fourth order (without it, one stage sees the wrong side and the error is first order).
  const PlanarPlantExample example = example_haply2diy_v3_plant();
  const Vec2 home = home_of(example);
  const auto run = [&](int substeps) {
    PlanarPlantParameters p = example.parameters;
    p.coulomb_N_m = Vec2{};
    PlanarSimulationConfig config;
    config.start_q_rad = example.home_q_rad;
    config.substeps_per_tick = substeps;
    config.hand.motion = PlanarHandMotion::circle;
    config.hand.stiffness_N_per_m = 500.0;
    config.hand.damping_N_s_per_m = 5.0;
    config.hand.circle_center_m = home;
    config.hand.circle_radius_m = 0.015;
    config.hand.speed_m_per_s = 0.1;
    PlanarPlant plant(p, config);
    for (int k = 0; k < 500; ++k) plant.advance(kTick_s);
    return plant.handle_m();
  };
  const Vec2 fine = run(64);
  const double error_1 = norm(run(1) - fine), error_2 = norm(run(2) - fine);
  CHECK(error_1 < 1e-8);
  CHECK(error_1 > 8.0 * error_2);
}
