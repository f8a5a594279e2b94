// The real-time loop's warming (engine/run/warm_tick.hpp) replays the last tick dry before
// each deadline. It must change nothing a tick computes: every tick of a run warmed before
// each tick is bit for bit the tick of the same run unwarmed (the simulated run does not
// warm), for built-in scenes, scripts that only read (called again), scripts with state,
// faulting or hooked scripts (never called again), and 2-D scenes.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/runner.hpp"
#include "engine/run/warm_tick.hpp"
#include "engine/scene/step.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

void put(std::vector<std::uint64_t>* out, double value) { out->push_back(std::bit_cast<std::uint64_t>(value)); }
void put(std::vector<std::uint64_t>* out, const Vec2& value) {
  put(out, value[0]);
  put(out, value[1]);
}
void put(std::vector<std::uint64_t>* out, const MotorCommand& command) {
  put(out, command.duty);
  out->push_back(command.direction_high ? 1 : 0);
}
void put(std::vector<std::uint64_t>* out, const PlanarMotorCommand& command) {
  put(out, command.motor[0]);
  put(out, command.motor[1]);
  put(out, command.torque_N_m);
  put(out, command.scale);
  out->push_back(command.saturated ? 1 : 0);
}

// What one tick computed and what the scripts show, as bits.
template <int N>
std::vector<std::uint64_t> tick_bits(const TickStateOf<N>& state) {
  std::vector<std::uint64_t> bits;
  bits.push_back(state.tick);
  put(&bits, state.t_s);
  put(&bits, state.x_m);
  put(&bits, state.v_m_per_s);
  put(&bits, state.effects_force_N);
  put(&bits, state.output_N);
  put(&bits, state.command);
  bits.push_back(state.script_calls);
  const SafetyCounters& c = state.safety.counters;
  for (const std::uint64_t count : {c.nonfinite_faults, c.outside_workspace_ticks, c.soft_start_ticks, c.clamped_ticks,
                                    c.slew_limited_ticks, c.position_hold_ticks, c.pose_hold_ticks,
                                    c.motor_saturated_ticks}) {
    bits.push_back(count);
  }
  for (const auto& script : state.scripts) {
    bits.push_back(script->memory_bytes());
    bits.push_back(script->allocation_count());
    bits.push_back(script->skipped_calls());
    bits.push_back(script->fault_count());
    put(&bits, script->fault_time_s());
  }
  return bits;
}

// A run of `scene` over `readings`, warmed before each tick as the real-time loop does (on
// some ticks twice, on some not at all) or not warmed; every tick's bits, and the scripts'
// dry calls.
template <int N>
struct Run {
  std::vector<std::vector<std::uint64_t>> ticks;
  std::vector<std::string> faults;
  std::uint64_t dry_calls{};
};
template <int N>
Run<N> run_ticks(const SceneOf<N>& scene, const std::vector<typename SceneParts<N>::Reading>& readings, bool warmed) {
  Run<N> run;
  TickStateOf<N> state = make_tick_state(scene);
  TickWarmerOf<N> warmer(scene);
  for (std::size_t i = 0; i < readings.size(); ++i) {
    if (warmed && i % 11 != 5) {
      warmer.warm(scene, state);
      if (i % 3 == 0) warmer.warm(scene, state);
    }
    warmer.note_reading(readings[i]);
    step(scene, readings[i], &state);
    collect_script_garbage(&state);
    run.ticks.push_back(tick_bits(state));
  }
  for (const auto& script : state.scripts) {
    run.faults.emplace_back(script->fault_message());
    run.dry_calls += script->dry_calls();
  }
  return run;
}

// A sweep of a Hapkit's sensor counts over the lab's workspace and back.
std::vector<std::int32_t> sweep_counts(int ticks) {
  std::vector<std::int32_t> counts;
  for (int i = 0; i < ticks; ++i) {
    counts.push_back(static_cast<std::int32_t>(std::lround(510.0 + 450.0 * std::sin(2.0 * M_PI * i / 1500.0))));
  }
  return counts;
}

// Runs `scene` warmed and unwarmed and checks every tick is the same; returns the dry calls.
template <int N>
std::uint64_t check_warming_changes_nothing(const SceneOf<N>& scene,
                                            const std::vector<typename SceneParts<N>::Reading>& readings) {
  const Run<N> plain = run_ticks(scene, readings, false);
  const Run<N> warmed = run_ticks(scene, readings, true);
  REQUIRE(plain.ticks.size() == warmed.ticks.size());
  for (std::size_t i = 0; i < plain.ticks.size(); ++i) {
    CAPTURE(i);
    REQUIRE(plain.ticks[i] == warmed.ticks[i]);
  }
  CHECK(plain.faults == warmed.faults);
  CHECK(plain.dry_calls == 0);
  return warmed.dry_calls;
}

Scene lua_scene(const std::string& source) {
  nlohmann::json effects = nlohmann::json::array();
  effects.push_back({{"type", "spring"}, {"stiffness", 50}});
  effects.push_back({{"type", "script"}, {"source", source}});
  return test::scene_from(nlohmann::json{{"effects", effects}}.dump());
}

}  // namespace

TEST_CASE("warm tick: built-in scenes compute the same warmed, tick by tick") {
  const std::vector<std::int32_t> counts = sweep_counts(4000);
  for (const char* file : {"environments/spring.json", "environments/wall.json", "environments/damper.json",
                           "environments/texture.json"}) {
    CAPTURE(file);
    check_warming_changes_nothing(load_environment_file(test::source_path(file)), counts);
  }
  check_warming_changes_nothing(test::scene_from(R"({"effects": [
    {"type": "spring", "stiffness": 100}, {"type": "damper", "damping": 1},
    {"type": "wall", "position": 0.01, "stiffness": 500, "solid": "above"},
    {"type": "texture", "width": 0.005, "damping": 2}]})"),
                                counts);
}

TEST_CASE("warm tick: a script that only reads is called again, and computes the same") {
  const std::vector<std::int32_t> counts = sweep_counts(3000);
  // The shipped spring and texture only read.
  for (const char* file : {"scripts/spring.lua", "scripts/texture.lua"}) {
    CAPTURE(file);
    CHECK(check_warming_changes_nothing(load_environment_file(test::source_path(file)), counts) > 2500);
  }
  // Reads of s (v and t too), params, upvalues and globals; branches; a division by s.x.
  const Scene reader = lua_scene(
      "params = {k = '200 N/m'}\n"
      "local gain = 0.5\n"
      "scale = 2\n"
      "function force(s)\n"
      "  if s.x > 0.01 then return -params.k * s.x * gain * scale + 1e-6 / s.x end\n"
      "  return -0.1 * s.v + 1e-3 * s.t\n"
      "end");
  CHECK(check_warming_changes_nothing(reader, counts) > 2500);
}

TEST_CASE("warm tick: a script with state is never called again") {
  const std::vector<std::int32_t> counts = sweep_counts(2000);
  // Each of these would compute differently if called once more per tick: a counter in an
  // upvalue, in a table, in a global (a global of the script's top level), and one that
  // makes a string (allocation).
  // The shipped wall keeps its contact state in upvalues (and calls math.exp).
  CHECK(check_warming_changes_nothing(load_environment_file(test::source_path("scripts/wall.lua")), counts) == 0);
  for (const char* source : {
           "needs = {velocity = false, time = false}\n"
           "local n = 0\n"
           "function force(s) n = n + 1 return 1e-4 * (n % 7) - s.x end",
           "needs = {velocity = false, time = false}\n"
           "local t = {0}\n"
           "function force(s) t[1] = t[1] + 1 return 1e-4 * (t[1] % 5) end",
           "needs = {velocity = false, time = false}\n"
           "count = 0\n"
           "function force(s) count = count + 1 return 1e-4 * (count % 3) end",
           "needs = {velocity = false, time = false}\n"
           "local t = {}\n"
           "function force(s) t.last = 'x' .. s.x return 0 end",
       }) {
    CAPTURE(source);
    CHECK(check_warming_changes_nothing(lua_scene(source), counts) == 0);
  }
}

TEST_CASE("warm tick: a script that faults, or runs hooked, is never called again") {
  const std::vector<std::int32_t> counts = sweep_counts(2000);
  // Returns nil once the handle passes 5 mm: disabled there, then skipped (counted alike).
  CHECK(check_warming_changes_nothing(
            lua_scene("function force(s) if s.x > 0.005 then return nil end return -s.x end"), counts) > 0);
  // A loop keeps the count hook, whose count carries over between calls.
  CHECK(check_warming_changes_nothing(
            lua_scene("function force(s) local f = 0 for i = 1, 3 do f = f - s.x end return f end"), counts) == 0);
  // A call keeps the call hook.
  CHECK(check_warming_changes_nothing(lua_scene("function force(s) return -math.abs(s.x) end"), counts) == 0);
}

TEST_CASE("warm tick: a planar scene computes the same warmed, tick by tick") {
  const PlanarScene scene = load_planar_environment_text(R"({"device": "haplink", "effects": [
    {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "inside"},
    {"type": "script", "file": "scripts/planar/mass_spring.lua"},
    {"type": "script", "file": "scripts/planar/bumps.lua"},
    {"type": "script", "source": "function force(s) return -10 * s.x, -10 * s.y + 0.1 * s.vy end"}]})",
                                                         "env.json", test::source_path(""));
  std::vector<PlanarReading> readings;
  for (int i = 0; i < 3000; ++i) {
    const double phase = 0.002 * i;
    readings.push_back(planar_reading_for(scene.device_model.model, Vec2{{0.3 * std::sin(phase), 0.2 * std::cos(phase)}}));
  }
  CHECK(check_warming_changes_nothing(scene, readings) > 2500);
}

namespace {

// Every tick's bits, as the run loop sees them.
struct Recorder : TickObserver {
  std::vector<std::vector<std::uint64_t>> ticks;
  void on_start(const TickState&) override { ticks.reserve(1000); }
  void on_tick(const TickState& state) noexcept override { ticks.push_back(tick_bits(state)); }
};

}  // namespace

TEST_CASE("warm tick: a real-time run computes what a simulated run computes" * doctest::test_suite("threaded")) {
  // The real-time loop warms before every deadline, the simulated one never: the ticks that
  // ran (a stall on a loaded machine may end the real-time run early) are the same.
  const Scene scene = lua_scene(
      "needs = {velocity = false}\n"
      "function force(s) if s.x > 0 then return -300 * s.x end return 1e-3 * s.t end");
  const auto record = [&](Pacing pacing) {
    SimulatedHapkit device(scene.device, SimulationConfig{});
    Recorder recorder;
    run_scene(scene, device, RunOptions{.duration_s = 0.5, .pacing = pacing}, &recorder);
    return recorder.ticks;
  };
  const auto simulated = record(Pacing::simulated_time);
  const auto real_time = record(Pacing::real_time);
  REQUIRE(real_time.size() > 100);
  for (std::size_t i = 0; i < real_time.size(); ++i) {
    CAPTURE(i);
    REQUIRE(real_time[i] == simulated[i]);
  }
}
