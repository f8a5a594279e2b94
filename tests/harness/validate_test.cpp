// The harness's verdicts, each check both ways: a scene that should pass passes, one
// that should fail fails for the right reason.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/harness/validate.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::scene_from;

namespace {

// Runs one scenario of `scene` with the default hand (and optional sensor noise), judged
// by `thresholds` (an environment's validate block).
ScenarioResult run(const Scene& scene, ScenarioKind kind, double noise_counts = -1.0,
                   const ValidateThresholds& thresholds = {}) {
  HarnessOptions options;
  options.noise_counts = noise_counts;
  options.thresholds = thresholds;
  const ForceField field = probe_force_field(scene, thresholds.stiff_threshold_N_per_m);
  return run_scenario(scene, field, build_scenario(kind, scene, field, options), options);
}

const CheckResult& check(const ScenarioResult& result, const std::string& name) {
  const auto found = std::find_if(result.checks.begin(), result.checks.end(),
                                  [&](const CheckResult& c) { return c.name == name; });
  REQUIRE(found != result.checks.end());
  return *found;
}

std::string wall(double stiffness_N_per_m) {
  return R"({"effects": [{"type": "wall", "position": "10 mm", "stiffness": )" +
         std::to_string(stiffness_N_per_m) + R"(, "solid": "above"}]})";
}

std::string spring(double stiffness_N_per_m) {
  return R"({"effects": [{"type": "spring", "stiffness": )" + std::to_string(stiffness_N_per_m) + "}]}";
}

// Colgate's bound for the Hapkit profile at 1 kHz: 2 * 0.4 N*s/m / 1 ms = 800 N/m.
constexpr double kBound_N_per_m = 800.0;

}  // namespace

TEST_CASE("validate: a wall at 0.3x the passivity bound is passive, at 3x it is not") {
  const ScenarioResult stable = run(scene_from(wall(0.3 * kBound_N_per_m)), ScenarioKind::press);
  CHECK(check(stable, "passivity").pass);
  // The observer measures K / K_max: created energy over the device's own dissipation.
  CHECK(stable.metrics.passivity.ratio == doctest::Approx(0.3).epsilon(0.1));
  CHECK(stable.pass);

  const ScenarioResult unstable = run(scene_from(wall(3.0 * kBound_N_per_m)), ScenarioKind::press);
  CHECK_FALSE(check(unstable, "passivity").pass);
  CHECK(unstable.metrics.passivity.ratio == doctest::Approx(3.0).epsilon(0.1));
  CHECK(unstable.metrics.passivity.net_J > 0.0);
  CHECK(unstable.metrics.passivity.grows);
  CHECK_FALSE(unstable.pass);
}

TEST_CASE("validate: the whole report agrees, and the bound is reported") {
  const ValidationReport stable = validate_scene(scene_from(wall(0.3 * kBound_N_per_m)), {}, {});
  CHECK(stable.pass);
  CHECK(stable.passivity_bound_N_per_m == doctest::Approx(kBound_N_per_m));
  CHECK(stable.stiffest_region_N_per_m == doctest::Approx(240.0).epsilon(0.01));
  CHECK(stable.scenarios.size() == 6);
  const ValidationReport unstable = validate_scene(scene_from(wall(3.0 * kBound_N_per_m)), {}, {});
  CHECK_FALSE(unstable.pass);
}

TEST_CASE("validate: the lab spring oscillates on release and dies out") {
  const Scene scene = load_environment_file(test::source_path("environments/spring.json"));
  const ScenarioResult result = run(scene, ScenarioKind::release);
  REQUIRE(result.metrics.oscillation.has_value());
  const OscillationMetrics& o = *result.metrics.oscillation;
  CHECK(o.half_cycles >= 3);
  const double natural_Hz = std::sqrt(100.0 / scene.device.plant.mass_kg) / (2.0 * M_PI);
  CHECK(o.frequency_Hz == doctest::Approx(natural_Hz).epsilon(0.1));
  CHECK(check(result, "limit_cycle").pass);
  CHECK(check(result, "growth").pass);
}

TEST_CASE("validate: a spring far above the bound keeps oscillating after release") {
  const ScenarioResult result = run(scene_from(spring(3.0 * kBound_N_per_m)), ScenarioKind::release);
  const OscillationMetrics& o = *result.metrics.oscillation;
  CHECK(o.half_cycles > 20);
  CHECK(o.residual_amplitude_m > 1e-3);
  CHECK_FALSE(check(result, "limit_cycle").pass);
  CHECK_FALSE(check(result, "growth").pass);
  CHECK_FALSE(check(result, "passivity").pass);
  // And below the bound it settles.
  const ScenarioResult calm = run(scene_from(spring(0.3 * kBound_N_per_m)), ScenarioKind::release);
  CHECK(check(calm, "limit_cycle").pass);
  CHECK(check(calm, "growth").pass);
}

TEST_CASE("validate: heavy damping with a noisy sensor is gritty, light damping is not") {
  const std::string damper = R"({"effects": [{"type": "damper", "damping": B}]})";
  const auto with = [&](const char* b) {
    std::string text = damper;
    return scene_from(text.replace(text.find('B'), 1, b));
  };
  const ScenarioResult light = run(with("1"), ScenarioKind::shake, /*noise_counts=*/1.0);
  CHECK(check(light, "jitter").pass);
  CHECK(light.pass);
  const ScenarioResult heavy = run(with("20"), ScenarioKind::shake, 1.0);
  CHECK_FALSE(check(heavy, "jitter").pass);
  CHECK(heavy.metrics.force_jitter_N > 0.3);
  CHECK(check(heavy, "passivity").pass);  // gritty, but a damper still only dissipates
}

TEST_CASE("validate: a discontinuous force field jolts: slew and capstan slip fail") {
  // A texture with huge damping: the force jumps at every band edge.
  const ScenarioResult texture = run(scene_from(R"({"effects": [
      {"type": "texture", "width": "5 mm", "damping": 50}]})"), ScenarioKind::sweep);
  CHECK_FALSE(check(texture, "slew").pass);
  CHECK_FALSE(check(texture, "slip").pass);
  CHECK(texture.metrics.slip_step_ticks > 0);
  CHECK(texture.metrics.max_step_1ms_N > 2.0);
  // The lab texture is smooth enough.
  const ScenarioResult lab = run(load_environment_file(test::source_path("environments/texture.json")),
                                 ScenarioKind::sweep);
  CHECK(check(lab, "slew").pass);
  CHECK(check(lab, "slip").pass);
}

TEST_CASE("validate: a sudden large step (a near-rigid wall) jolts and chatters while held") {
  const ScenarioResult hold = run(scene_from(wall(1e5)), ScenarioKind::hold);
  CHECK_FALSE(check(hold, "slip").pass);
  CHECK_FALSE(check(hold, "slew").pass);
  CHECK_FALSE(check(hold, "limit_cycle").pass);
  CHECK(hold.metrics.oscillation->frequency_Hz > 10.0);
  // The lab wall held the same way is quiet.
  const ScenarioResult lab = run(load_environment_file(test::source_path("environments/wall.json")),
                                 ScenarioKind::hold);
  CHECK(lab.pass);
  CHECK(lab.metrics.oscillation->residual_amplitude_m < 1e-4);
}

TEST_CASE("validate: force limit, time at the limit and penetration, both ways") {
  // A stiff spring pushed across the workspace sits at the force limit.
  const ScenarioResult stiff = run(scene_from(spring(2400)), ScenarioKind::sweep);
  CHECK_FALSE(check(stiff, "time_at_limit").pass);
  CHECK(stiff.metrics.max_output_N == doctest::Approx(6.0));
  CHECK(check(stiff, "max_force").pass);  // never above the limit: the clamp holds

  // A lower max_force in the validate block fails the same run.
  const Environment strict = test::environment_from(R"({"validate": {"max_force": "3 N", "max_penetration": "5 mm"},
      "effects": [{"type": "wall", "position": "10 mm", "stiffness": 500, "solid": "above"}]})");
  const ScenarioResult sweep = run(strict.scene, ScenarioKind::sweep, -1.0, strict.validate);
  CHECK_FALSE(check(sweep, "max_force").pass);
  CHECK(check(sweep, "max_force").threshold == 3.0);
  CHECK_FALSE(check(sweep, "penetration").pass);
  CHECK(sweep.metrics.max_penetration_m == doctest::Approx(0.009).epsilon(0.05));
  const ScenarioResult lab = run(load_environment_file(test::source_path("environments/wall.json")),
                                 ScenarioKind::sweep);
  CHECK(check(lab, "max_force").pass);
  CHECK(check(lab, "penetration").pass);
  CHECK(check(lab, "time_at_limit").pass);
}

TEST_CASE("validate: script faults and tick compute time have thresholds") {
  const ScenarioResult result = run(scene_from(spring(100)), ScenarioKind::hold);
  CHECK(check(result, "script").pass);  // no script faults
  CHECK(check(result, "script").value == 0.0);
  const CheckResult& compute = check(result, "tick_compute");
  CHECK(compute.threshold == doctest::Approx(0.5e-3));  // half the period by default
  CHECK(compute.value > 0.0);
  CHECK(compute.pass);
  // A threshold no computer meets fails.
  const Environment slow = test::environment_from(R"({"validate": {"max_tick_compute": "1e-12 s"}, "effects": []})");
  const ScenarioResult strict = run(slow.scene, ScenarioKind::hold, -1.0, slow.validate);
  CHECK_FALSE(check(strict, "tick_compute").pass);
}

TEST_CASE("validate: a script that errors, loops forever or jolts fails for the right reason") {
  // A runtime error half a second in: the script is disabled and counted as an error.
  const ScenarioResult erring = run(scene_from(R"({"effects": [{"type": "script", "source":
    "function force(s) if s.t > 0.5 then local y = nil; return y.z end return -50 * s.x end"}]})"),
                                    ScenarioKind::hold);
  CHECK_FALSE(check(erring, "script").pass);
  CHECK(check(erring, "script").value == 1.0);
  // The message says what, where in the script, and when and where the handle was.
  CHECK(check(erring, "script").detail ==
        "1 errors, 0 budget overruns: test.json#/effects/0/source:1: attempt to index a nil value (local 'y') "
        "(t 0.501 s, x 8.02 mm)");
  // An endless loop after a while: stopped by the instruction budget, counted as an overrun.
  const ScenarioResult looping = run(scene_from(R"({"effects": [{"type": "script", "source":
    "function force(s) while s.t > 0.3 do end return 0 end"}]})"),
                                     ScenarioKind::hold);
  CHECK(check(looping, "script").detail.starts_with(
      "0 errors, 1 budget overruns: test.json#/effects/0/source:1: instruction budget exceeded"));
  CHECK(check(looping, "script").detail.ends_with("(t 0.301 s, x 10.02 mm)"));
  // A script that jolts: 4 N switched on and off every 50 ms trips the capstan-slip check.
  const ScenarioResult jolting = run(scene_from(R"({"effects": [{"type": "script", "source":
    "function force(s) if math.floor(s.t / 0.05) % 2 == 1 then return 4 end return 0 end"}]})"),
                                     ScenarioKind::hold);
  CHECK(check(jolting, "script").pass);
  CHECK_FALSE(check(jolting, "slip").pass);
}

TEST_CASE("validate: runs are deterministic to the bit") {
  const Scene scene = load_environment_file(test::source_path("environments/wall_corridor.json"));
  HarnessOptions options;
  options.noise_counts = 1.5;
  options.seed = 7;
  const ValidationReport a = validate_scene(scene, {}, options);
  const ValidationReport b = validate_scene(scene, {}, options);
  REQUIRE(a.scenarios.size() == b.scenarios.size());
  for (std::size_t i = 0; i < a.scenarios.size(); ++i) {
    CAPTURE(a.scenarios[i].scenario.name);
    const auto& ra = a.scenarios[i].records;
    const auto& rb = b.scenarios[i].records;
    REQUIRE(ra.size() == rb.size());
    CHECK(std::equal(ra.begin(), ra.end(), rb.begin(), [](const TickRecord& x, const TickRecord& y) {
      return x.x_true_m == y.x_true_m && x.output_N == y.output_N && x.v_m_per_s == y.v_m_per_s;
    }));
    CHECK(a.scenarios[i].metrics.passivity.created_J == b.scenarios[i].metrics.passivity.created_J);
  }
}
