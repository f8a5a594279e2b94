// Script effects inside scenes: .lua environments, JSON script effects and their errors,
// declared needs, and a Lua spring that matches the built-in spring to the last bit.
#include <doctest/doctest.h>

#include "engine/devices/kinematics.hpp"
#include "engine/scene/step.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::load_error;
using hapscene::test::scene_from;

TEST_CASE("script scene: a .lua file is a one-effect environment with its defaults") {
  const Scene scene = load_environment_file(test::source_path("scripts/spring.lua"));
  CHECK(scene.name == "spring");
  REQUIRE(scene.effects.size() == 1);
  const auto& script = std::get<ScriptEffect>(scene.effects[0]);
  CHECK(script.file == test::source_path("scripts/spring.lua"));
  CHECK(scene.script_count == 1);
  CHECK_FALSE(scene.needs.velocity);  // the script declares needs = {velocity = false}
  CHECK(test::input_error_of([] { load_environment_file("scripts/nope.lua"); }) ==
        "scripts/nope.lua: cannot open file");
}

TEST_CASE("script scene: the Lua spring equals the built-in spring to the last bit") {
  const Scene builtin = load_environment_file(test::source_path("environments/spring.json"));
  const Scene lua = load_environment_file(test::source_path("scripts/spring.lua"));
  TickState a = make_tick_state(builtin);
  TickState b = make_tick_state(lua);
  for (int counts = -3000; counts <= 4000; counts += 7) {
    const double x_m = counts_to_position_m(builtin.device_model.kinematics, counts);
    EffectInput input{.x_m = x_m, .v_m_per_s = 0.0, .t_s = 0.0, .dt_s = 0.001};
    REQUIRE(sum_effects_N(builtin, input, a.scripts) == sum_effects_N(lua, input, b.scripts));
  }
  // And through whole ticks, sensor to motor command.
  TickState c = make_tick_state(builtin);
  TickState d = make_tick_state(lua);
  for (int raw = 50; raw < 972; raw += 3) {
    step(builtin, raw, &c);
    step(lua, raw, &d);
    REQUIRE(c.output_N == d.output_N);
    REQUIRE(c.command.duty == d.command.duty);
  }
}

TEST_CASE("script scene: script effects in JSON, with parameters, next to built-ins") {
  const Scene scene = scene_from(R"({"effects": [
    {"type": "spring", "stiffness": 10},
    {"type": "script", "file": "../scripts/grating.lua", "params": {"amplitude": "0.5 N"}},
    {"type": "script", "source": "function force(s) return 1 end"}]})");
  CHECK(scene.script_count == 2);
  CHECK(std::get<ScriptEffect>(scene.effects[1]).instance_index == 0);
  CHECK(std::get<ScriptEffect>(scene.effects[2]).instance_index == 1);
  CHECK(scene.needs.velocity);  // the inline script declares nothing: assumed to read v and t
  TickState state = make_tick_state(scene);
  const EffectInput input{.x_m = 0.00125, .v_m_per_s = 0.0, .t_s = 0.0, .dt_s = 0.001};
  CHECK(sum_effects_N(scene, input, state.scripts) == doctest::Approx(-10 * 0.00125 - 0.5 + 1.0));
}

TEST_CASE("script scene: load errors name the file and the place") {
  CHECK(load_error(R"({"effects": [{"type": "script"}]})") ==
        "test.json: /effects/0: a script needs exactly one of \"file\" and \"source\"");
  CHECK(load_error(R"({"effects": [{"type": "script", "file": "a.lua", "source": "x"}]})") ==
        "test.json: /effects/0: a script needs exactly one of \"file\" and \"source\"");
  CHECK(load_error(R"({"effects": [{"type": "script", "file": "missing.lua"}]})")
            .starts_with("test.json: /effects/0/file: "));
  CHECK(load_error(R"({"effects": [{"type": "script", "source": "function force(s) return 0 end",
    "params": [1]}]})") == "test.json: /effects/0/params: expected an object, got array");
  CHECK(load_error(R"({"effects": [{"type": "script", "file": "../scripts/grating.lua",
    "params": {"amplitud": 1}}]})").starts_with("test.json: /effects/0/params/amplitud: "));
  CHECK(load_error(R"({"effects": [{"type": "script", "source": "function force(s) return 0 end",
    "limits": {"instructions_per_call": 5}}]})") ==
        "test.json: /effects/0/limits/instructions_per_call: must be in [100, 100000000], got 5");
  // A syntax error reads file:line, with the inline source named by its JSON pointer.
  CHECK(load_error(R"({"effects": [{"type": "script", "source": "function force(s)\n return 1 +\nend"}]})")
            .starts_with("test.json#/effects/0/source:3:"));
  // A disabled script is not even loaded.
  CHECK(load_error(R"({"effects": [{"type": "script", "source": "this is not lua", "enabled": false}]})") ==
        "(no error)");
}

TEST_CASE("script scene: every script limit can be set from the environment, within its range") {
  const Scene scene = scene_from(R"({"effects": [{"type": "script", "source": "function force(s) return 0 end",
    "limits": {"instructions_per_call": 20000, "instructions_at_load": 50000000, "memory_bytes": 1048576,
               "allocation_bytes_per_call": 65536, "string_bytes": 1024, "wall_time_per_call": "0.5 ms",
               "log_rate": "2 Hz", "log_burst": 5}}]})");
  const ScriptLimits& limits = std::get<ScriptEffect>(scene.effects[0]).program->limits;
  CHECK(limits.instructions_per_call == 20000);
  CHECK(limits.instructions_at_load == 50000000);
  CHECK(limits.memory_bytes == 1048576);
  CHECK(limits.allocation_bytes_per_call == 65536);
  CHECK(limits.string_bytes == 1024);
  CHECK(limits.wall_time_per_call_s == doctest::Approx(0.0005));
  CHECK(limits.log_messages_per_s == 2.0);
  CHECK(limits.log_burst == 5);

  const auto error_for = [](const std::string& key_value) {
    return load_error(R"({"effects": [{"type": "script", "source": "function force(s) return 0 end",
      "limits": {)" + key_value + "}}]}");
  };
  CHECK(error_for(R"("instructions_at_load": 10)") ==
        "test.json: /effects/0/limits/instructions_at_load: must be in [100, 1000000000], got 10");
  CHECK(error_for(R"("string_bytes": 100)") ==
        "test.json: /effects/0/limits/string_bytes: must be in [256, 16777216], got 100");
  CHECK(error_for(R"("log_burst": 65)") == "test.json: /effects/0/limits/log_burst: must be in [0, 64], got 65");
  CHECK(error_for(R"("log_rate": "2 mm")").starts_with("test.json: /effects/0/limits/log_rate: "));
  CHECK(error_for(R"("log_rate": -1)").starts_with("test.json: /effects/0/limits/log_rate: "));
  CHECK(error_for(R"("instruction_at_load": 1000)").starts_with(
      "test.json: /effects/0/limits/instruction_at_load: unknown key"));
}
