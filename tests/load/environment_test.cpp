// Loading environment files: every shipped environment loads, values convert, and every
// class of bad input fails with a message that names the file and the place.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "engine/base/json_source.hpp"
#include "engine/load/environment.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::load_error;
using hapscene::test::scene_from;

TEST_CASE("environment: the shipped lab environments load with their values") {
  const Scene wall = load_environment_file(test::source_path("environments/wall.json"));
  REQUIRE(wall.effects.size() == 1);
  const auto& w = std::get<Wall>(wall.effects[0]);
  CHECK(w.position_m == doctest::Approx(0.010));
  CHECK(w.stiffness_N_per_m == 500.0);
  CHECK(w.solid_above);
  CHECK(wall.rate_hz == 1000.0);
  CHECK(wall.device.name == "hapkit3");

  for (const char* name : {"spring", "wall", "damper", "texture", "wall_corridor"}) {
    CAPTURE(name);
    const Scene scene =
        load_environment_file(test::source_path("environments/" + std::string(name) + ".json"));
    CHECK_FALSE(scene.effects.empty());
  }
}

TEST_CASE("environment: defaults, units and the compiled scene's needs") {
  const Scene scene = scene_from(R"({
    "rate_hz": "2 kHz",
    "effects": [{"type": "spring", "stiffness": "0.1 N/mm"},
                {"type": "texture", "width": "5 mm", "damping": 0.5}]})");
  CHECK(scene.name == "test");
  CHECK(scene.rate_hz == 2000.0);
  CHECK(scene.period_s == 0.0005);
  const auto& spring = std::get<Spring>(scene.effects[0]);
  CHECK(spring.stiffness_N_per_m == doctest::Approx(100.0));
  CHECK(spring.center_m == 0.0);
  const auto& texture = std::get<Texture>(scene.effects[1]);
  CHECK(texture.spacing_m == texture.width_m);
  CHECK(texture.offset_m == 0.0);
  CHECK(texture.period_m == doctest::Approx(0.010));
  CHECK(scene.needs.velocity);
  CHECK_FALSE(scene.needs.time);

  const Scene springs_only = scene_from(R"({"effects": [{"type": "spring", "stiffness": 50},
    {"type": "wall", "position": 0.01, "stiffness": 500, "solid": "below"}]})");
  CHECK_FALSE(springs_only.needs.velocity);
  CHECK_FALSE(springs_only.needs.time);
}

TEST_CASE("environment: a disabled effect is not compiled") {
  const Scene scene = scene_from(R"({"effects": [
    {"type": "damper", "damping": 1, "enabled": false},
    {"type": "spring", "stiffness": 50}]})");
  REQUIRE(scene.effects.size() == 1);
  CHECK(std::holds_alternative<Spring>(scene.effects[0]));
  CHECK_FALSE(scene.needs.velocity);
}

TEST_CASE("environment: the safety block lowers the device's limits, never raises them") {
  const Scene scene = scene_from(R"({"safety": {"max_force": "3 N", "slew_limit": "1 N/ms",
    "workspace": ["-20 mm", "20 mm"], "soft_start": "1 s"}, "effects": []})");
  CHECK(scene.safety.max_force_N == 3.0);
  CHECK(scene.safety.slew_limit_N_per_s == 1000.0);
  CHECK(scene.safety.max_step_N == doctest::Approx(1.0));
  CHECK(scene.safety.workspace_min_m == doctest::Approx(-0.02));
  CHECK(scene.safety.soft_start_s == 1.0);

  CHECK(load_error(R"({"safety": {"max_force": "10 N"}, "effects": []})") ==
        "test.json: /safety/max_force: must not exceed the device's 6 N");
  CHECK(load_error(R"({"safety": {"soft_start": 0}, "effects": []})") ==
        "test.json: /safety/soft_start: must not be shorter than the device's 0.5 s");
  CHECK(load_error(R"({"safety": {"workspace": [-1, 0]}, "effects": []})") ==
        "test.json: /safety/workspace: must lie within the device's workspace [-0.05, 0.045] m");
}

TEST_CASE("environment: malformed JSON reports line and column") {
  CHECK(load_error("{\n  \"effects\": [\n    {\"type\": \"spring\",}\n  ]\n}") ==
        "test.json:3:23: syntax error while parsing object key - unexpected '}'; expected string literal");
  CHECK(load_error("") ==
        "test.json:1:1: syntax error while parsing value - unexpected end of input; expected '[', '{', or a literal");
}

TEST_CASE("environment: bad values name the JSON pointer") {
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": 50},
                                    {"type": "wall", "position": 0.01, "stiffness": -5, "solid": "above"}]})") ==
        "test.json: /effects/1/stiffness: must be >= 0, got -5 N/m");
  CHECK(load_error(R"({"effects": [{"type": "texture", "width": 0, "damping": 1}]})") ==
        "test.json: /effects/0/width: must be > 0, got 0 m");
  CHECK(load_error(R"({"effects": [{"type": "texture", "width": "-5 mm", "damping": 1}]})") ==
        "test.json: /effects/0/width: must be > 0, got -0.005 m");
  CHECK(load_error(R"({"effects": [{"type": "damper", "damping": -1}]})") ==
        "test.json: /effects/0/damping: must be >= 0, got -1 N*s/m");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": "50 mm"}]})") ==
        "test.json: /effects/0/stiffness: expected a stiffness (N/m), got a length (\"50 mm\")");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": "50 N/mx"}]})") ==
        "test.json: /effects/0/stiffness: unknown unit \"N/mx\" (did you mean \"N/m\"?)");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": 1e999}]})") ==
        "test.json:1:46: number out of range: 1e999");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": "inf N/m"}]})") ==
        "test.json: /effects/0/stiffness: value must be finite, got \"inf N/m\"");
  CHECK(load_error(R"({"rate_hz": "5 Hz", "effects": []})") ==
        "test.json: /rate_hz: must be between 10 Hz and 100 kHz");
}

TEST_CASE("environment: wrong types, missing keys, unknown keys and types") {
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": true}]})") ==
        "test.json: /effects/0/stiffness: expected a stiffness in N/m or a string with a unit, got boolean");
  CHECK(load_error(R"({"effects": [{"type": "spring"}]})") ==
        "test.json: /effects/0: missing required key \"stiffness\"");
  CHECK(load_error(R"({"effects": [{"stiffness": 5}]})") ==
        "test.json: /effects/0: missing required key \"type\"");
  CHECK(load_error(R"({"effects": [{"type": "sprnig", "stiffness": 5}]})") ==
        "test.json: /effects/0/type: unknown effect type \"sprnig\" (did you mean \"spring\"?)");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stifness": 5, "stiffness": 5}]})") ==
        "test.json: /effects/0/stifness: unknown key \"stifness\" (did you mean \"stiffness\"?)");
  CHECK(load_error(R"({"effects": [{"type": "wall", "position": 0, "stiffness": 5, "solid": "abve"}]})") ==
        "test.json: /effects/0/solid: \"abve\" is not one of \"above\", \"below\" (did you mean \"above\"?)");
  // A required key written wrong is named as the misspelling it is, wherever it is read.
  CHECK(load_error(R"({"effect": []})") ==
        "test.json: /effect: unknown key \"effect\" (did you mean \"effects\"?)");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stifness": 5}]})") ==
        "test.json: /effects/0/stifness: unknown key \"stifness\" (did you mean \"stiffness\"?)");
  CHECK(load_error(R"({"effects": [{"type": "wall", "positon": "10 mm", "stiffness": 5}]})") ==
        "test.json: /effects/0/positon: unknown key \"positon\" (did you mean \"position\"?)");
  CHECK(load_error(R"({"effects": [{"typ": "spring", "stiffness": 5}]})") ==
        "test.json: /effects/0/typ: unknown key \"typ\" (did you mean \"type\"?)");
  // No guess for a key far from every expected one.
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": 5, "zebra": 1}]})") ==
        "test.json: /effects/0/zebra: unknown key \"zebra\"");
  CHECK(load_error(R"({"name": "x"})") == "test.json: missing required key \"effects\"");
  CHECK(load_error(R"({"efects": [], "effects": []})") ==
        "test.json: /efects: unknown key \"efects\" (did you mean \"effects\"?)");
  CHECK(load_error(R"({"effects": {}})") ==
        "test.json: /effects: expected an array of effects, got object");
  CHECK(load_error(R"([1, 2])") == "test.json: expected an object, got array");
  CHECK(load_error(R"({"effects": [3]})") == "test.json: /effects/0: expected an object, got number");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": 1, "stiffness": 2}]})") ==
        "test.json: /effects/0/stiffness: key \"stiffness\" appears twice");
}

TEST_CASE("environment: device profiles by name and by path") {
  CHECK(load_error(R"({"device": "hapkit2", "effects": []})") ==
        "test.json: /device: unknown device profile \"hapkit2\" (did you mean \"hapkit3\"?)");
  const Scene by_path = scene_from(R"({"device": "devices/hapkit3.json", "effects": []})");
  CHECK(by_path.device.drive.motor_constant_N_m == 0.03);
  CHECK(test::input_error_of([] { scene_from(R"({"device": "nowhere/x.json", "effects": []})"); })
            .ends_with("nowhere/x.json: cannot open file"));
}

TEST_CASE("environment: files that are missing, too large or too deep") {
  CHECK(test::input_error_of([] { load_environment_file("/nonexistent/wall.json"); }) ==
        "/nonexistent/wall.json: cannot open file");

  const std::filesystem::path big = std::filesystem::temp_directory_path() / "hapscene_big.json";
  {
    std::ofstream out(big);
    out << "{\"effects\": [], \"description\": \"" << std::string(kMaxJsonFileBytes, 'x') << "\"}";
  }
  CHECK(test::input_error_of([&] { load_environment_file(big.string()); }) ==
        big.string() + ": file larger than 1048576 bytes");
  std::filesystem::remove(big);

  const std::string deep = std::string(100, '[') + std::string(100, ']');
  CHECK(load_error(deep) == "test.json:1:33: nesting deeper than 32 levels");
  // Brackets inside strings do not count.
  CHECK(load_error("{\"description\": \"" + std::string(100, '[') + "\", \"effects\": []}") ==
        "(no error)");
}

TEST_CASE("environment: the validate block sets the harness's thresholds") {
  const Environment defaults = test::environment_from(R"({"effects": []})");
  CHECK(defaults.validate.max_force_N < 0.0);  // derived from the safety limit
  CHECK(defaults.validate.max_passivity_ratio == 1.0);
  const Environment environment = test::environment_from(R"({"validate": {"max_force": "3 N", "max_time_at_limit": 0.2,
      "max_slew": "1 N/ms", "max_slip_ticks": 5, "max_passivity_ratio": 0.8,
      "max_residual_amplitude": "0.1 mm", "max_amplitude_growth": 0.5, "max_penetration": "8 mm",
      "max_force_jitter": "0.05 N", "max_tick_compute": "100 us", "max_script_faults": 2,
      "stiff_threshold": "300 N/m", "press_force": "2 N", "release_from": "-15 mm"}, "effects": []})");
  const ValidateThresholds& t = environment.validate;
  CHECK(t.max_force_N == 3.0);
  CHECK(t.max_time_at_limit_fraction == 0.2);
  CHECK(t.max_slew_N_per_s == doctest::Approx(1000.0));
  CHECK(t.max_slip_ticks == 5);
  CHECK(t.max_passivity_ratio == 0.8);
  CHECK(t.max_residual_amplitude_m == doctest::Approx(1e-4));
  CHECK(t.max_amplitude_growth == 0.5);
  CHECK(t.max_penetration_m == doctest::Approx(0.008));
  CHECK(t.max_force_jitter_N == 0.05);
  CHECK(t.max_tick_compute_s == doctest::Approx(1e-4));
  CHECK(t.max_script_faults == 2);
  CHECK(t.stiff_threshold_N_per_m == 300.0);
  CHECK(t.press_force_N == 2.0);
  CHECK(t.release_from_m == doctest::Approx(-0.015));
}

TEST_CASE("environment: validate block errors name the key") {
  CHECK(load_error(R"({"validate": {"max_force": -1}, "effects": []})") ==
        "test.json: /validate/max_force: must be > 0, got -1 N");
  CHECK(load_error(R"({"validate": {"max_time_at_limit": 2}, "effects": []})") ==
        "test.json: /validate/max_time_at_limit: must be a fraction in [0, 1], got 2");
  CHECK(load_error(R"({"validate": {"max_slip_ticks": 1.5}, "effects": []})") ==
        "test.json: /validate/max_slip_ticks: expected a whole number, got 1.5");
  CHECK(load_error(R"({"validate": {"max_penetration": "3 N"}, "effects": []})") ==
        "test.json: /validate/max_penetration: expected a length (m), got a force (\"3 N\")");
  CHECK(load_error(R"({"validate": {"max_forse": 3}, "effects": []})") ==
        "test.json: /validate/max_forse: unknown key \"max_forse\" (did you mean \"max_force\"?)");
  CHECK(load_error(R"({"validate": [], "effects": []})") ==
        "test.json: /validate: expected an object, got array");
}

TEST_CASE("profile: capstan slip limits default when a profile leaves them out") {
  const DeviceProfile hapkit3 = load_device_profile("hapkit3", ".");
  CHECK(hapkit3.limits.slip_force_N == 5.0);
  CHECK(hapkit3.limits.slip_step_N == 2.0);
}
