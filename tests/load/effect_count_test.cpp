// One environment's effects are bounded in number, and its script effects together in
// number, memory and load time (docs/reference/lua.md, "Limits"), so no file can make a load
// grow without bound.
#include <doctest/doctest.h>

#include <chrono>
#include <string>

#include "engine/base/object_reader.hpp"
#include "engine/effects/script_effect.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::load_error;
using hapscene::test::scene_from;

namespace {

// An environment of `count` copies of `effect`.
std::string environment_of(std::size_t count, const std::string& effect) {
  std::string effects;
  for (std::size_t i = 0; i < count; ++i) effects += (i == 0 ? "" : ", ") + effect;
  return R"({"effects": [)" + effects + "]}";
}

const std::string kScript = R"({"type": "script", "source": "function force(s) return 0 end"})";

}  // namespace

TEST_CASE("effect count: at most 256 effects, counted before any is read") {
  const std::string spring = R"({"type": "spring", "stiffness": 100})";
  CHECK(scene_from(environment_of(256, spring)).effects.size() == 256);
  CHECK(load_error(environment_of(257, spring)) ==
        "test.json: /effects: has 257 effects; one environment may have at most 256");
  // Disabled ones count too: the array itself is bounded.
  CHECK(load_error(environment_of(257, R"({"type": "spring", "stiffness": 100, "enabled": false})")) ==
        "test.json: /effects: has 257 effects; one environment may have at most 256");
}

TEST_CASE("effect count: at most 64 script effects, refused before any script loads") {
  CHECK(scene_from(environment_of(64, kScript)).script_count == 64);
  // The 65th is named; the syntax error in the last one is never reached.
  const std::string broken = R"({"type": "script", "source": "function force(s) return 0"})";
  std::string text = environment_of(70, kScript);
  text.replace(text.rfind(kScript), kScript.size(), broken);
  CHECK(load_error(text) ==
        "test.json: /effects/64: more than 64 script effects in one environment (each has its own Lua state)");
  // A disabled script is never loaded and does not count.
  const std::string disabled = R"({"type": "script", "source": "function force(s) return 0 end", "enabled": false})";
  CHECK(scene_from(environment_of(64, kScript).replace(13, 0, disabled + ", ")).script_count == 64);
}

TEST_CASE("effect count: the script effects' memory caps add up to at most 1 GiB") {
  const std::string big = R"({"type": "script", "source": "function force(s) return 0 end",
                              "limits": {"memory_bytes": 1073741824}})";
  CHECK(scene_from(environment_of(1, big)).script_count == 1);
  // Named at the effect that passes the sum: its key when written, else the effect.
  CHECK(load_error(R"({"effects": [)" + kScript + ", " + big + "]}") ==
        "test.json: /effects/1/limits/memory_bytes: the script effects' memory_bytes add up to 1077936128 here, more "
        "than the 1073741824 (1 GiB) one environment may have");
  CHECK(load_error(R"({"effects": [)" + big + ", " + kScript + "]}") ==
        "test.json: /effects/1: the script effects' memory_bytes add up to 1077936128 here, more "
        "than the 1073741824 (1 GiB) one environment may have");
  // 64 scripts at the default 4 MiB stay well within it.
  CHECK(scene_from(environment_of(64, kScript)).script_count == 64);
}

TEST_CASE("effect count: the shared load budget is 10 s, or the largest load_time") {
  const nlohmann::json defaults = nlohmann::json::parse("[" + kScript + ", " + kScript + "]");
  CHECK(plan_script_loads(defaults, "test.json", "/effects").total_s == 10.0);
  const nlohmann::json longer = nlohmann::json::parse(
      "[" + kScript + R"(, {"type": "script", "source": "function force(s) return 0 end",
                          "limits": {"load_time": "30 s"}}])");
  CHECK(plan_script_loads(longer, "test.json", "/effects").total_s == 30.0);
  // A bad limits block is left for the effect's own parse to report.
  const nlohmann::json bad = nlohmann::json::parse(
      R"([{"type": "script", "source": "x", "limits": {"load_time": "1 N"}}])");
  CHECK(plan_script_loads(bad, "test.json", "/effects").total_s == 10.0);
}

TEST_CASE("effect count: a script load stops when the environment's shared budget runs out") {
  // Within its own load_time (5 s), but only 0.3 s of the environment's budget is left.
  const nlohmann::json slow = nlohmann::json::parse(
      R"({"type": "script", "source": "for i = 1, 1e9 do end function force(s) return 0 end",
          "limits": {"instructions_at_load": 1000000000}})");
  ObjectReader reader(slow, "/effects/3", "test.json");
  ScriptLoadBudget budget{10.0, 9.7};
  const auto started = std::chrono::steady_clock::now();
  const std::string message = test::input_error_of([&] { ScriptEffect::parse(reader, budget); });
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  MESSAGE("stopped after " << took_s << " s");
  CHECK(message.starts_with("test.json: /effects/3: the script effects of this environment share 10 s to load (the "
                            "larger of 10 s and their largest load_time), and this one was stopped when it ran out: "));
  CHECK(message.find("load time limit exceeded") != std::string::npos);
  CHECK(took_s < 2.0);
  CHECK(budget.used_s >= 10.0);

  // Nothing left: the next script is refused before it starts.
  const nlohmann::json quick = nlohmann::json::parse(kScript);
  ObjectReader next(quick, "/effects/4", "test.json");
  CHECK(test::input_error_of([&] { ScriptEffect::parse(next, budget); }) ==
        "test.json: /effects/4: the script effects of this environment share 10 s to load (the larger of 10 s and "
        "their largest load_time), and the scripts before this one used it all");
}

TEST_CASE("effect count: a script loaded on what is left of the budget keeps its own load_time for each run") {
  const nlohmann::json quick = nlohmann::json::parse(kScript);
  ObjectReader reader(quick, "/effects/0", "test.json");
  ScriptLoadBudget budget{10.0, 9.0};
  const ScriptEffect effect = ScriptEffect::parse(reader, budget);
  CHECK(effect.program->limits.load_time_s == 5.0);
  CHECK(budget.used_s > 9.0);
  CHECK(budget.used_s < 9.5);
}
