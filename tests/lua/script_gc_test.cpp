// Memory in the tick: a non-allocating script allocates nothing per call, and the
// collector never runs inside force(); the host does small steps between ticks.
#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;
using test::run_inline;

// Calls force `calls` times at 1 kHz, collecting garbage after each call as a runner does.
void run_ticks(ScriptInstance* script, int calls, bool collect) {
  for (int i = 0; i < calls; ++i) {
    const double t = i * 0.001;
    script->force_N(at(0.02 * std::sin(t), 0.02 * std::cos(t), t));
    if (collect) script->collect_garbage();
  }
}

TEST_CASE("gc: the lab spring and texture allocate nothing per call") {
  for (const std::string name : {"spring.lua", "texture.lua", "wall.lua", "mass_spring.lua"}) {
    CAPTURE(name);
    auto script = ScriptInstance::create(test::compile_shipped(name));
    script->reset();
    // Warm-up over the same path: the first call that goes one call level deeper (wall.lua
    // calling math.exp on its first contact) grows Lua's call-info list once.
    run_ticks(script.get(), 10000, true);
    const std::uint64_t allocations = script->allocation_count();
    const std::size_t bytes = script->memory_bytes();
    run_ticks(script.get(), 10000, true);
    CHECK(script->allocation_count() == allocations);
    CHECK(script->memory_bytes() == bytes);
    CHECK_FALSE(script->disabled());
  }
}

TEST_CASE("gc: the collector does not run inside force()") {
  // Each call makes a table that becomes garbage at once.
  auto script = run_inline("function force(s) local t = { s.x } return t[1] end");
  const std::size_t start = script->memory_bytes();
  run_ticks(script.get(), 1000, false);
  const std::size_t grown = script->memory_bytes();
  CHECK(grown > start + 50'000);  // about 1000 tables of 56 bytes and more, never collected
  // The host's steps reclaim it.
  script->collect_garbage(100'000);
  CHECK(script->memory_bytes() < start + 4096);
  CHECK_FALSE(script->disabled());
}

TEST_CASE("gc: one small step per tick keeps an allocating script bounded") {
  auto script = run_inline("function force(s) local t = { s.x, s.v, s.t } return t[1] end");
  const std::size_t start = script->memory_bytes();
  std::size_t peak = 0;
  for (int i = 0; i < 50'000; ++i) {
    script->force_N(at(0.001 * (i % 10), 0.0, i * 0.001));
    script->collect_garbage(1);
    peak = std::max(peak, script->memory_bytes());
  }
  CHECK(peak < start + (256u << 10));
  CHECK_FALSE(script->disabled());
}

TEST_CASE("gc: without the host's steps the cap still holds, by emergency collections") {
  ScriptLimits limits;
  limits.memory_bytes = 256u << 10;
  auto script = run_inline("function force(s) local t = { s.x, s.v, s.t } return t[1] end", limits);
  run_ticks(script.get(), 20'000, false);
  CHECK_FALSE(script->disabled());
  CHECK(script->memory_bytes() <= limits.memory_bytes);
}

}  // namespace
}  // namespace hapscene
