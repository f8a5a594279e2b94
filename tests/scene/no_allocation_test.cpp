// The tick allocates nothing: a counting global operator new around many steps.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/runner.hpp"
#include "engine/run/warm_tick.hpp"
#include "engine/scene/step.hpp"
#include "tests/support.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// GCC pairs the replaced operator new with std::free and warns; both are ours and match.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

// Counts every allocation in the test binary (the counter is only read around the loop).
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// The nothrow form too (std::stable_sort's buffer uses it): AddressSanitizer supplies its
// own for any form not replaced here, which would then be freed by the delete below.
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace hapscene;

TEST_CASE("step: ten thousand ticks of every lab effect allocate nothing") {
  const Scene scene = test::scene_from(R"({"effects": [
    {"type": "spring", "stiffness": 100}, {"type": "damper", "damping": 1},
    {"type": "wall", "position": 0.01, "stiffness": 500, "solid": "above"},
    {"type": "texture", "width": 0.005, "damping": 2}]})");
  SimulatedHapkit device(scene.device, SimulationConfig{});
  TickState state = make_tick_state(scene);
  const long before = g_allocations.load();
  for (int i = 0; i < 10000; ++i) {
    step(scene, device.read(), &state);
    device.write(state.command);
    device.advance(scene.period_s);
  }
  CHECK(g_allocations.load() - before == 0);
  CHECK(state.tick == 10000);

  // The counter does see allocations.
  const long counted = g_allocations.load();
  auto* probe = new std::vector<double>(8);
  delete probe;
  CHECK(g_allocations.load() - counted >= 1);
}

TEST_CASE("run: the simulated-time runner allocates nothing per tick") {
  const Scene scene = test::scene_from(R"({"effects": [{"type": "wall", "position": 0.01,
    "stiffness": 500, "solid": "above"}]})");
  const auto allocations_for = [&](double duration_s) {
    SimulatedHapkit device(scene.device, SimulationConfig{});
    const long before = g_allocations.load();
    run_scene(scene, device, RunOptions{.duration_s = duration_s, .pacing = Pacing::simulated_time}, nullptr);
    return g_allocations.load() - before;
  };
  // Set-up may allocate; a run ten times longer must not allocate more.
  CHECK(allocations_for(10.0) == allocations_for(1.0));
}

TEST_CASE("step: a planar scene's 2-D script effects allocate nothing per tick") {
  const PlanarScene scene = load_planar_environment_text(R"({"device": "haplink", "effects": [
    {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "inside"},
    {"type": "script", "file": "scripts/planar/mass_spring.lua"},
    {"type": "script", "file": "scripts/planar/bumps.lua"}]})",
                                                         "env.json", test::source_path(""));
  TickStateOf<2> state = make_tick_state(scene);
  const PlanarModel& model = scene.device_model.model;
  const auto run_ticks = [&](int ticks) {
    for (int i = 0; i < ticks; ++i) {
      const double phase = 0.002 * static_cast<double>(state.tick);
      step(scene, planar_reading_for(model, Vec2{{0.3 * std::sin(phase), 0.2 * std::cos(phase)}}), &state);
    }
  };
  run_ticks(1000);  // warm-up: Lua's call-info list grows once
  const long before = g_allocations.load();
  run_ticks(10000);
  CHECK(g_allocations.load() - before == 0);
  CHECK(state.script_calls == 2 * 11000);
  CHECK_FALSE(state.scripts[0]->disabled());
  CHECK_FALSE(state.scripts[1]->disabled());
}

TEST_CASE("warm tick: the real-time loop's dry tick allocates nothing, 1-D and 2-D") {
  // Built-in effects and a script that is called again (it only reads).
  const Scene scene = test::scene_from(R"({"effects": [
    {"type": "wall", "position": 0.01, "stiffness": 500, "solid": "above"},
    {"type": "script", "source": "function force(s) return -100 * s.x - 0.1 * s.v end"}]})");
  TickState state = make_tick_state(scene);
  TickWarmer warmer(scene);
  const auto run_ticks = [&](int ticks) {
    for (int i = 0; i < ticks; ++i) {
      const auto raw = static_cast<std::int32_t>(500 + 400 * std::sin(0.003 * static_cast<double>(state.tick)));
      warmer.warm(scene, state);
      warmer.note_reading(raw);
      step(scene, raw, &state);
    }
  };
  run_ticks(1000);
  long before = g_allocations.load();
  run_ticks(10000);
  CHECK(g_allocations.load() - before == 0);
  CHECK(state.scripts[0]->dry_calls() > 10000);

  const PlanarScene planar = load_planar_environment_text(R"({"device": "haplink", "effects": [
    {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "inside"},
    {"type": "script", "source": "function force(s) return -10 * s.x, -10 * s.y end"}]})",
                                                          "env.json", test::source_path(""));
  TickStateOf<2> planar_state = make_tick_state(planar);
  TickWarmerOf<2> planar_warmer(planar);
  const auto run_planar_ticks = [&](int ticks) {
    for (int i = 0; i < ticks; ++i) {
      const double phase = 0.002 * static_cast<double>(planar_state.tick);
      const PlanarReading reading =
          planar_reading_for(planar.device_model.model, Vec2{{0.3 * std::sin(phase), 0.2 * std::cos(phase)}});
      planar_warmer.warm(planar, planar_state);
      planar_warmer.note_reading(reading);
      step(planar, reading, &planar_state);
    }
  };
  run_planar_ticks(1000);
  before = g_allocations.load();
  run_planar_ticks(10000);
  CHECK(g_allocations.load() - before == 0);
  CHECK(planar_state.scripts[0]->dry_calls() > 10000);
}
