// Scenario construction and the open-loop force-field probe.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/harness/scenario.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

TEST_CASE("force field: a wall is one stiff region with a pressable edge") {
  const Scene scene = load_environment_file(test::source_path("environments/wall.json"));
  const ForceField field = probe_force_field(scene, 200.0);
  REQUIRE(field.regions.size() == 1);
  CHECK(field.regions[0].low_m == doctest::Approx(0.010).epsilon(1e-3));
  CHECK(field.regions[0].high_m == doctest::Approx(scene.safety.workspace_max_m).epsilon(1e-3));
  CHECK(field.regions[0].low_is_edge);
  CHECK_FALSE(field.regions[0].high_is_edge);
  CHECK(field.regions[0].stiffness_N_per_m == doctest::Approx(500.0).epsilon(1e-6));
  CHECK(field.penetration_m(0.015) == doctest::Approx(0.005).epsilon(1e-3));
  CHECK(field.penetration_m(0.005) == 0.0);
}

TEST_CASE("force field: the stored energy of a spring is K x^2 / 2") {
  const Scene scene = scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  const ForceField field = probe_force_field(scene, 200.0);
  CHECK(field.regions.empty());  // 100 N/m is below the threshold
  const double zero_J = field.potential_at_J(0.0);
  CHECK(field.potential_at_J(0.02) - zero_J == doctest::Approx(0.5 * 100 * 0.02 * 0.02).epsilon(1e-4));
  CHECK(field.potential_at_J(-0.03) - zero_J == doctest::Approx(0.5 * 100 * 0.03 * 0.03).epsilon(1e-4));
}

TEST_CASE("force field: the corridor has two walls facing each other") {
  const Scene scene = load_environment_file(test::source_path("environments/wall_corridor.json"));
  const ForceField field = probe_force_field(scene, 200.0);
  REQUIRE(field.regions.size() == 2);
  CHECK(field.regions[0].high_m == doctest::Approx(-0.030).epsilon(1e-3));
  CHECK(field.regions[0].high_is_edge);
  CHECK(field.regions[1].low_m == doctest::Approx(0.030).epsilon(1e-3));
  CHECK(field.regions[1].low_is_edge);
}

TEST_CASE("scenario: press pushes into every wall edge at three speeds and backs out") {
  const Scene scene = load_environment_file(test::source_path("environments/wall_corridor.json"));
  const ForceField field = probe_force_field(scene, 200.0);
  const Scenario press = build_scenario(ScenarioKind::press, scene, field, HarnessOptions{});
  REQUIRE(press.applicable);
  CHECK(press.simulation.hand.motion == HandMotion::path);
  const auto& path = press.simulation.hand.path;
  // Deepest references: 15 mm (3 N at 200 N/m) beyond each edge, kept 3 mm inside the
  // workspace (42 mm and -47 mm), three times each.
  int beyond_top = 0;
  int beyond_bottom = 0;
  for (const HandWaypoint& p : path) {
    beyond_top += p.x_m > 0.040 ? 1 : 0;
    beyond_bottom += p.x_m < -0.040 ? 1 : 0;
  }
  CHECK(beyond_top == 6);      // arrive and leave after the hold, at three speeds
  CHECK(beyond_bottom == 6);
  CHECK(press.description.find("up into 30 mm") != std::string::npos);
  CHECK(press.description.find("down into -30 mm") != std::string::npos);
  CHECK(press.duration_s == doctest::Approx(path.back().t_s));
}

TEST_CASE("scenario: press has nothing to do without a stiff region") {
  const Scene scene = load_environment_file(test::source_path("environments/damper.json"));
  const ForceField field = probe_force_field(scene, 200.0);
  const Scenario press = build_scenario(ScenarioKind::press, scene, field, HarnessOptions{});
  CHECK_FALSE(press.applicable);
}

TEST_CASE("scenario: release lets go and watches, free has no hand, names parse") {
  const Scene scene = load_environment_file(test::source_path("environments/spring.json"));
  const ForceField field = probe_force_field(scene, 200.0);
  const Scenario release = build_scenario(ScenarioKind::release, scene, field, HarnessOptions{});
  REQUIRE(release.watch_from_s.has_value());
  const VirtualHand hand(release.simulation.hand, 0.0);
  CHECK(hand.gripping(*release.watch_from_s - 0.01));
  CHECK_FALSE(hand.gripping(*release.watch_from_s + 0.01));
  CHECK(hand.reference_m(*release.watch_from_s - 0.01) == doctest::Approx(0.02));

  HarnessOptions options;
  options.free_start_m = -0.003;
  const Scenario free = build_scenario(ScenarioKind::free, scene, field, options);
  CHECK(free.simulation.hand.motion == HandMotion::none);
  CHECK(free.simulation.start_x_m == -0.003);

  CHECK(scenario_kind_named("shake") == ScenarioKind::shake);
  CHECK_FALSE(scenario_kind_named("wobble").has_value());
}

TEST_CASE("hand: path, shake and grip") {
  HandConfig config;
  config.motion = HandMotion::path;
  config.path = {{0.0, 0.0, true}, {1.0, 0.01, true}, {2.0, 0.01, false}};
  const VirtualHand path(config, 0.0);
  CHECK(path.reference_m(0.5) == doctest::Approx(0.005));
  CHECK(path.reference_velocity_m_per_s(0.5) == doctest::Approx(0.01));
  CHECK(path.gripping(1.5));
  CHECK_FALSE(path.gripping(2.5));
  CHECK(path.force_N(2.5, 0.0, 0.0) == 0.0);
  CHECK(path.added_mass_kg(2.5) == 0.0);

  config.motion = HandMotion::shake;
  config.hold_m = 0.001;
  config.shake_amplitude_m = 0.002;
  config.shake_frequency_Hz = 10.0;
  config.mass_kg = 0.02;
  const VirtualHand shake(config, 0.0);
  CHECK(shake.reference_m(0.025) == doctest::Approx(0.003));  // a quarter period
  CHECK(shake.reference_velocity_m_per_s(0.0) == doctest::Approx(0.002 * 2 * M_PI * 10));
  CHECK(shake.added_mass_kg(0.3) == 0.02);
}
