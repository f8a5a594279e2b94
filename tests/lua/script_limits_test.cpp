// Limits: a script that loops, allocates or recurses without bound is stopped within one
// call, cannot catch the stop, and is disabled with a message naming the limit and line.
#include <chrono>

#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;
using test::kProbeSuffix;

using test::run_inline;

// Runs force once at x = 1 cm (the check at load ran at x = 0) and returns the fault.
std::string fault_at_1cm(ScriptInstance* script) {
  CHECK(script->force_N(at(0.01)) == 0.0);
  CHECK(script->disabled());
  return std::string(script->fault_message());
}

TEST_CASE("limits: an endless loop is stopped within the call's budget, quickly") {
  auto script = run_inline(
      "function force(s)\n"
      "  if s.x > 0 then\n"
      "    while true do end\n"
      "  end\n"
      "  return 0\n"
      "end");
  const auto start = std::chrono::steady_clock::now();
  const double force = script->force_N(at(0.01));
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(force == 0.0);
  CHECK(script->disabled());
  CHECK(script->fault_message() ==
        "t.lua:3: instruction budget exceeded (100000 instructions per call)");
  CHECK(script->fault() == ScriptFault::instruction_budget);
  MESSAGE("a runaway loop was stopped after " << elapsed_s * 1e6 << " us");
  CHECK(elapsed_s < 0.05);  // about 0.3 ms on a laptop; generous for loaded CI machines
}

TEST_CASE("limits: pcall, xpcall and error handlers cannot swallow the stop") {
  auto with_pcall = run_inline(
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  while true do\n"
      "    pcall(function() while true do end end)\n"
      "  end\n"
      "end");
  CHECK(fault_at_1cm(with_pcall.get()).find("instruction budget exceeded") != std::string::npos);

  auto with_handler = run_inline(
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  for i = 1, 1e9 do\n"
      "    xpcall(function() while true do end end, function() while true do end end)\n"
      "  end\n"
      "  return 1\n"
      "end");
  CHECK(fault_at_1cm(with_handler.get()).find("instruction budget exceeded") != std::string::npos);
}

TEST_CASE("limits: a coroutine that never yields is caught by the same budget") {
  auto fresh = run_inline(
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  return coroutine.wrap(function() while true do end end)()\n"
      "end");
  CHECK(fault_at_1cm(fresh.get()) ==
        "t.lua:3: instruction budget exceeded (100000 instructions per call)");

  // Created while loading, first resumed while running; its error is caught by resume,
  // and the caller is stopped on its next instruction anyway.
  auto from_load = run_inline(
      "local co = coroutine.create(function() while true do end end)\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  local ok = coroutine.resume(co)\n"
      "  return 1\n"
      "end");
  CHECK(fault_at_1cm(from_load.get()) ==
        "t.lua:1: instruction budget exceeded (100000 instructions per call)");
}

TEST_CASE("limits: C functions are charged for their work") {
  // Sorting 20 000 numbers is about 300 000 comparisons: over a 100 000 budget.
  auto sort = run_inline(
      "local t = {}\n"
      "for i = 1, 20000 do t[i] = (i * 7919) % 20000 end\n"
      "function force(s)\n"
      "  if s.x > 0 then table.sort(t) end\n"
      "  return 0\n"
      "end");
  CHECK(fault_at_1cm(sort.get()) ==
        "t.lua:4: instruction budget exceeded (100000 instructions per call; this call was "
        "charged 300000)");

  // A lying __len would make table.insert shift a billion slots inside C.
  auto insert = run_inline(
      "local t = setmetatable({}, { __len = function() return 1e9 end })\n"
      "function force(s)\n"
      "  if s.x > 0 then table.insert(t, 1, 0) end\n"
      "  return 0\n"
      "end");
  CHECK(fault_at_1cm(insert.get()) ==
        "t.lua:3: instruction budget exceeded (100000 instructions per call; this call was "
        "charged 1000000000)");
}

TEST_CASE("limits: cheap uses of charged functions stay cheap") {
  // Appending, reading one byte of a long string, unpacking a few: no large charge.
  auto script = run_inline(
      "local t, text = {}, string.rep('x', 4000)\n"
      "function force(s)\n"
      "  for i = 1, 2000 do t[#t + 1] = 1; table.insert(t, 2); table.remove(t) end\n"
      "  local sum = 0\n"
      "  for i = 1, 1000 do sum = sum + text:byte(i) + select('#', table.unpack(t, 1, 3)) end\n"
      "  return sum\n"
      "end");
  CHECK(script->force_N(at(0.0)) == 1000.0 * (120 + 3));
  CHECK_FALSE(script->disabled());
}

TEST_CASE("limits: allocation per call and the memory cap stop memory bombs") {
  auto bomb = run_inline(
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  local t = {}\n"
      "  while true do t[#t + 1] = { 1, 2, 3 } end\n"
      "end");
  CHECK(fault_at_1cm(bomb.get()) == "t.lua:4: allocation limit exceeded (262144 bytes per call)");
  CHECK(bomb->fault() == ScriptFault::memory_limit);

  // With a per-call limit above the cap, the cap stops it; garbage is collected
  // first (an emergency collection), live data is not.
  ScriptLimits limits;
  limits.allocation_bytes_per_call = 16 * limits.memory_bytes;
  limits.instructions_per_call = 10'000'000;
  auto hoarder = run_inline(
      "local kept = {}\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  while true do kept[#kept + 1] = { 1, 2, 3 } end\n"
      "end",
      limits);
  CHECK(fault_at_1cm(hoarder.get()) == "t.lua:4: memory limit exceeded (4194304 bytes)");
  CHECK(hoarder->memory_bytes() <= limits.memory_bytes);

  // While loading, the cap applies too.
  CHECK(test::script_load_error("local t = {}\nfor i = 1, 1e7 do t[i] = i end") ==
        "t.lua:2: memory limit exceeded (4194304 bytes)");
}

TEST_CASE("limits: strings are capped, so no single operation walks a huge one") {
  CHECK(test::script_load_error("function force(s) return #string.rep('x', 1e9) end") ==
        std::string("t.lua:1: string limit exceeded (string.rep would make 1000000000 bytes; "
                    "limit 4096)") +
            std::string(kProbeSuffix));
  CHECK(test::script_load_error("function force(s) return #('ab'):rep(3000) end") ==
        std::string("t.lua:1: string limit exceeded (string.rep would make 6000 bytes; limit "
                    "4096)") +
            std::string(kProbeSuffix));
  auto doubling = run_inline(
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  local text = 'x'\n"
      "  while true do text = text .. text end\n"
      "end");
  CHECK(fault_at_1cm(doubling.get()) == "t.lua:4: string limit exceeded (4096 bytes per string)");
  // Exactly at the limit is fine.
  CHECK(test::script_load_error("local a = string.rep('x', 4095) .. 'y'\nfunction force(s) return #a end") == "");
}

TEST_CASE("limits: runaway recursion is an error, not a crash") {
  auto lua_stack = run_inline(
      "local function depth(n) return depth(n + 1) + 1 end\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  return depth(1)\n"
      "end");
  CHECK(fault_at_1cm(lua_stack.get()) ==
        "t.lua:1: allocation limit exceeded (262144 bytes per call); the call stack is over 1000 "
        "levels deep (runaway recursion?)");

  // Recursion through metamethods nests C calls: Lua stops it at 200 levels.
  auto c_stack = run_inline(
      "local t = setmetatable({}, { __index = function(t, k) return t[k] end })\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  return t.anything\n"
      "end");
  CHECK(fault_at_1cm(c_stack.get()) == "t.lua:1: C stack overflow");
}

TEST_CASE("limits: the top-level chunk has its own, larger budget") {
  CHECK(test::script_load_error("while true do end") ==
        "t.lua:1: instruction budget exceeded (10000000 instructions while loading)");
  // A lookup table of 100 000 entries is fine.
  CHECK(test::script_load_error("local t = {}\nfor i = 1, 100000 do t[i] = math.sin(i) end\n"
                   "function force(s) return t[1] end") == "");
}

TEST_CASE("limits: an optional wall-clock limit per call") {
  ScriptLimits limits;
  limits.instructions_per_call = std::int64_t{1} << 50;
  limits.instructions_at_load = std::int64_t{1} << 50;
  limits.wall_time_per_call_s = 0.002;
  auto script = run_inline(
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  while true do end\n"
      "end",
      limits);
  CHECK(fault_at_1cm(script.get()) == "t.lua:3: time limit exceeded (2 ms per call)");
  CHECK(script->fault() == ScriptFault::time_limit);
}

TEST_CASE("limits: limits are checked when compiling") {
  ScriptLimits limits;
  limits.memory_bytes = 1000;
  CHECK(test::script_load_error("function force(s) return 0 end", {}, limits) ==
        "environments/lab.json: script limits: memory_bytes must be at least 65536 (64 KiB)");
  limits = {};
  limits.instructions_per_call = 10;
  CHECK(test::script_load_error("function force(s) return 0 end", {}, limits) ==
        "environments/lab.json: script limits: instructions_per_call must be at least 100");
  // The smallest limits still run a spring.
  limits.instructions_per_call = 100;
  limits.memory_bytes = 64u << 10;
  limits.allocation_bytes_per_call = 1024;
  auto small = ScriptInstance::create(
      test::compile_inline("function force(s) return -100 * s.x end", limits));
  CHECK(small->force_N(at(0.01)) == -1.0);
}

TEST_CASE("limits: a disabled script stays at 0 N, counts skipped calls, and reset keeps it off") {
  auto script = run_inline(
      "function reset() end\n"
      "function force(s)\n"
      "  if s.x > 0 then while true do end end\n"
      "  return 1\n"
      "end");
  CHECK(script->force_N(at(-0.01, 0.0, 0.25)) == 1.0);
  CHECK(script->force_N(at(0.01, 0.0, 0.5)) == 0.0);
  CHECK(script->fault_count() == 1);
  CHECK(script->fault_time_s() == 0.5);
  script->reset();
  CHECK(script->disabled());
  CHECK(script->force_N(at(-0.01)) == 0.0);
  CHECK(script->force_N(at(-0.01)) == 0.0);
  CHECK(script->skipped_calls() == 2);
  CHECK(script->fault_count() == 1);
}

}  // namespace
}  // namespace hapscene
