// Hostile scripts: whatever a script does, one force()/reset() call or one load ends
// within its budget's time (docs/reference/lua.md, "What bounds a call"). Each case is C work
// that the instruction count does not see at its real cost; without its fix each took
// seconds to forever. The time bounds are loose (a loaded 2-core machine), the faults
// exact.
#include <algorithm>
#include <chrono>
#include <ctime>

#include <nlohmann/json.hpp>

#include "engine/base/object_reader.hpp"
#include "engine/effects/script_effect.hpp"
#include "tests/lua/script_test_support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using test::at;
using test::script_load_error;
using test::run_inline;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double thread_cpu_s() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Calls force once at x = 1 cm (the check at load ran at x = 0) and returns its time.
double timed_force(ScriptInstance* script, double* force_N = nullptr, double* cpu_s = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_s = thread_cpu_s();
  const double force = script->force_N(at(0.01));
  if (cpu_s != nullptr) *cpu_s = thread_cpu_s() - cpu_start_s;
  if (force_N != nullptr) *force_N = force;
  return seconds_since(start);
}

// After a hostile script, a new instance of an ordinary one works.
void check_engine_still_works() {
  auto spring = run_inline("function force(s) return -100 * s.x end");
  CHECK(spring->force_N(at(0.01)) == -1.0);
}

// ---- Lengths reported by __len ----------------------------------------------------------

// A __len that answers 0 the first time it is asked and 2^30 after: the wrapper charged
// 0, and the original, asking again, would loop 2^30 times in C (forever, for remove).
std::string changing_len_script(const std::string& call) {
  return "local asked = 0\n"
         "local t = setmetatable({}, { __len = function()\n"
         "  asked = asked + 1\n"
         "  if asked == 1 then return 0 end\n"
         "  return 1 << 30\n"
         "end })\n"
         "function force(s)\n"
         "  if s.x <= 0 then return 0 end\n"
         "  asked = 0\n"
         "  pcall(function() " + call + " end)\n"
         "  return asked\n"
         "end";
}

TEST_CASE("hostile: a __len that changes its answer is asked once, and the work is what was charged") {
  for (const char* call : {"table.remove(t, 1)", "table.insert(t, 1, 'x')", "table.sort(t)",
                           "table.concat(t)", "table.unpack(t)"}) {
    CAPTURE(call);
    auto script = run_inline(changing_len_script(call));
    double force = -1;
    const double elapsed_s = timed_force(script.get(), &force);
    CHECK(elapsed_s < 1.0);
    CHECK(force == 1.0);  // the length was asked once
    CHECK_FALSE(script->disabled());
  }
  check_engine_still_works();
}

TEST_CASE("hostile: a negative __len costs nothing and loops nowhere") {
  auto script = run_inline(
      "local t = setmetatable({}, { __len = function() return -(1 << 40) end })\n"
      "function force(s)\n"
      "  table.insert(t, 1, 'x'); table.remove(t, 1); table.sort(t)\n"
      "  return select('#', table.unpack(t)) + #table.concat(t)\n"
      "end");
  double force = -1;
  CHECK(timed_force(script.get(), &force) < 1.0);
  CHECK(force == 0.0);
  CHECK_FALSE(script->disabled());
}

TEST_CASE("hostile: the proxy for a fixed length reads and writes through to the table") {
  auto script = run_inline(
      "local data = { 3, 1, 2 }\n"
      "local t = setmetatable({}, { __len = function() return #data end,\n"
      "  __index = data, __newindex = data })\n"
      "function force(s)\n"
      "  data[1], data[2], data[3], data[4] = 3, 1, 2, nil\n"
      "  table.sort(t)\n"
      "  table.insert(t, 1, 0)\n"
      "  table.remove(t, 2)\n"
      "  return data[1] * 100 + data[2] * 10 + data[3] + (data[4] and 1000 or 0) +\n"
      "         (#table.concat(t) == 3 and 0 or 5000)\n"
      "end");
  CHECK(script->force_N(at(0.0)) == 23.0);  // {0, 2, 3}
  CHECK_FALSE(script->disabled());
}

// ---- "Did you mean": searched once, for the reported error ----------------------------

TEST_CASE("hostile: failed lookups caught by pcall cost one instruction each, not a search") {
  // 20 000 globals of the typo's length: each search used to compare every one.
  auto script = run_inline(
      "for i = 1, 20000 do _G[string.format('name%05d', i)] = i end\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  local f = function() return nameXXXXX end\n"
      "  while true do pcall(f) end\n"
      "end");
  const double elapsed_s = timed_force(script.get());
  MESSAGE("20 000 globals, failed lookups until the budget ran out: " << elapsed_s * 1e3 << " ms");
  CHECK(elapsed_s < 1.0);
  // Each error message is a new string: the allocation limit or the budget stops it.
  CHECK(script->disabled());
  check_engine_still_works();
}

TEST_CASE("hostile: the reported error still gets its suggestion, a crowd of candidates gets none") {
  auto near = run_inline(
      "local stiffness = 1\nfunction force(s)\n  if s.x > 0 then return stifness end\n"
      "  return 0\nend");
  CHECK(near->force_N(at(0.01)) == 0.0);
  CHECK(near->fault_message() == "t.lua:3: undefined global 'stifness'");  // a local: no global near

  auto global = run_inline(
      "stiffness = 1\nfunction force(s)\n  if s.x > 0 then return stifness end\n  return 0\nend");
  CHECK(global->force_N(at(0.01)) == 0.0);
  CHECK(global->fault_message() ==
        "t.lua:3: undefined global 'stifness' (did you mean 'stiffness'?)");

  // Caught first, then the same lookup fails uncaught: the reported one is searched.
  auto caught = run_inline(
      "function force(s)\n  pcall(function() return s.xx end)\n"
      "  if s.x > 0 then return s.xx end\n  return 0\nend");
  CHECK(caught->force_N(at(0.01)) == 0.0);
  CHECK(caught->fault_message() == "t.lua:3: s has no field 'xx' (did you mean 's.x'?)");

  // Over 256 names within reach of the typo's length: no suggestion, whatever the order.
  auto crowd = run_inline(
      "for i = 1, 300 do _G[string.format('name%03d', i)] = i end\n"
      "function force(s)\n  if s.x > 0 then return name1000 end\n  return 0\nend");
  CHECK(crowd->force_N(at(0.01)) == 0.0);
  CHECK(crowd->fault_message() == "t.lua:3: undefined global 'name1000'");
}

// ---- Costly instructions: the time backstop ------------------------------------------

TEST_CASE("hostile: next() over a huge sparse table is stopped by the time backstop") {
  // 131 072 hash slots and one key: every next(t) scans them all (about 30 us).
  ScriptLimits limits;
  limits.memory_bytes = 16u << 20;
  auto script = run_inline(
      "local t = {}\n"
      "for i = 1, 100000 do t[i * 7 + 0.5] = true end\n"
      "for i = 1, 99999 do t[i * 7 + 0.5] = nil end\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  while true do next(t) end\n"
      "end",
      limits);
  double cpu_s = 0;
  const double elapsed_s = timed_force(script.get(), nullptr, &cpu_s);
  MESSAGE("sparse next() until the backstop: " << elapsed_s * 1e3 << " ms, " << cpu_s * 1e3
                                               << " ms of CPU (backstop "
                                               << call_time_backstop_s(limits) * 1e3 << " ms)");
  CHECK(cpu_s < 0.3);
  CHECK(script->fault() == ScriptFault::time_limit);
  CHECK(std::string(script->fault_message()).find("t.lua:6: time backstop exceeded (100 ms of CPU time per call") == 0);
  CHECK(elapsed_s < 1.0);
  check_engine_still_works();
}

TEST_CASE("hostile: reset() has the same backstop as force()") {
  ScriptLimits limits;
  limits.memory_bytes = 16u << 20;
  auto script = run_inline(
      "local t, armed = {}, false\n"
      "for i = 1, 100000 do t[i * 7 + 0.5] = true end\n"
      "for i = 1, 99999 do t[i * 7 + 0.5] = nil end\n"
      "function reset()\n"
      "  if armed then while true do next(t) end end\n"
      "  armed = true\n"
      "end\n"
      "function force(s) return 0 end",
      limits);
  script->reset();  // arms it (the instance is fresh: the check at load ran on another)
  CHECK_FALSE(script->disabled());
  const double cpu_start_s = thread_cpu_s();
  script->reset();
  CHECK(thread_cpu_s() - cpu_start_s < 0.3);
  CHECK(script->fault() == ScriptFault::time_limit);
  CHECK(std::string(script->fault_message()).find("t.lua:5: time backstop exceeded") == 0);
}

TEST_CASE("hostile: lookups of hash-colliding keys are stopped by the time backstop") {
  // Integer keys that are all multiples of the hash modulus share one chain: each lookup
  // of a missing one walks all 6000.
  ScriptLimits limits;
  limits.memory_bytes = 16u << 20;
  auto script = run_inline(
      "local t, m = {}, 8191\n"
      "for i = 1, 6000 do t[i * m] = i end\n"
      "for i = 6001, 8000 do t[-i] = i end\n"  // fill the table so it keeps 8192 slots
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  local k = 9000 * m\n"
      "  while true do local _ = t[k] end\n"
      "end",
      limits);
  double cpu_s = 0;
  const double elapsed_s = timed_force(script.get(), nullptr, &cpu_s);
  MESSAGE("colliding lookups until the budget or the backstop: " << elapsed_s * 1e3 << " ms, "
          << cpu_s * 1e3 << " ms of CPU: " << script->fault_message());
  CHECK(script->disabled());
  CHECK(cpu_s < 0.3);
  CHECK(elapsed_s < 1.0);
}

TEST_CASE("hostile: the backstop does not fire on a long but ordinary call") {
  // 10^6 instructions of plain Lua: about 5-30 ms, far below its 1 s backstop; the result
  // is the instruction budget, exactly as without a backstop.
  ScriptLimits limits;
  limits.instructions_per_call = 1'000'000;
  auto script = run_inline(
      "function force(s)\n  local a = 0\n  for i = 1, 300000 do a = a + i end\n  return a\nend",
      limits);
  CHECK(script->force_N(at(0.01)) == 45000150000.0);
  CHECK_FALSE(script->disabled());
  CHECK(call_time_backstop_s(limits) == doctest::Approx(1.0));
  CHECK(call_time_backstop_s(ScriptLimits{}) == doctest::Approx(0.1));
}

// ---- Metatables: frozen, no weak tables, bounded chains -------------------------------

TEST_CASE("hostile: weak tables, long and looping __index chains are refused at setmetatable") {
  CHECK(script_load_error("setmetatable({}, { __mode = 'k' })") ==
        "t.lua:1: setmetatable: weak tables (__mode) are not allowed in scripts (the collector "
        "clears them in one step that cannot be interrupted)");
  // A loop: Lua would follow it 2000 times inside one instruction.
  CHECK(script_load_error("local c = {}\nc.__index = c\nsetmetatable(c, c)").find(
            "t.lua:3: setmetatable: this table is the __index or __newindex of another table") == 0);
  CHECK(script_load_error("local a, b = {}, {}\nsetmetatable(a, { __index = b })\n"
                   "setmetatable(b, { __newindex = a })")
            .find("t.lua:3: setmetatable: this table is the __index") == 0);
  // 16 tables deep is fine, 17 is not.
  const std::string chain =
      "local t = {}\nfor i = 1, %d do t = setmetatable({}, { __index = t }) end\n"
      "function force(s) return t.x or 0 end";
  char source[200];
  std::snprintf(source, sizeof source, chain.c_str(), 16);
  CHECK(script_load_error(source) == "");
  std::snprintf(source, sizeof source, chain.c_str(), 17);
  CHECK(script_load_error(source) ==
        "t.lua:2: setmetatable: __index/__newindex chains longer than 16 tables are not allowed "
        "in scripts");
}

TEST_CASE("hostile: a metatable is frozen when set, getmetatable still answers the script's table") {
  auto script = run_inline(
      "local mt = { __index = function() return 1 end }\n"
      "local t = setmetatable({}, mt)\n"
      "local weak = setmetatable({}, mt)\n"
      "mt.__index = function() return 2 end\n"  // no effect: frozen
      "mt.__mode = 'k'\n"                          // no effect: not weak
      "weak[{}] = true\n"
      "function force(s)\n"
      "  return t.x * 10 + (getmetatable(t) == mt and 1 or 0) + (next(weak) and 100 or 0)\n"
      "end");
  script->collect_garbage(1000);
  CHECK(script->force_N(at(0.0)) == 111.0);
  CHECK_FALSE(script->disabled());
  // Protection still works, and the usual class idiom does too.
  CHECK(script_load_error("local t = setmetatable({}, { __metatable = 'no' })\nsetmetatable(t, {})") ==
        "t.lua:2: cannot change a protected metatable");
  CHECK(script_load_error("local Base = {}\nBase.__index = Base\nfunction Base.get(self) return self.v end\n"
                   "local Derived = setmetatable({}, Base)\nDerived.__index = Derived\n"
                   "local obj = setmetatable({ v = 3 }, Derived)\nassert(obj:get() == 3)\n"
                   "setmetatable(obj, nil)\nsetmetatable(obj, Derived)\n"
                   "function force(s) return obj:get() end") == "");
}

TEST_CASE("hostile: a collector step in the tick's slack is bounded by the heap") {
  // 3 MiB of small tables, all touched every call (so the atomic step re-traverses them),
  // and garbage every call so that the collector keeps running.
  ScriptLimits limits;
  limits.memory_bytes = 8u << 20;
  auto script = run_inline(
      "local cells = {}\n"
      "for i = 1, 40000 do cells[i] = { i } end\n"
      "local n = 0\n"
      "function force(s)\n"
      "  n = n + 1\n"
      "  for i = 1, 40 do cells[(n * 40 + i) % 40000 + 1] = { n } end\n"
      "  return 0\n"
      "end",
      limits);
  double worst_s = 0.0;
  for (int call = 0; call < 3000; ++call) {
    script->force_N(at(0.0));
    const double cpu_start_s = thread_cpu_s();
    script->collect_garbage();
    worst_s = std::max(worst_s, thread_cpu_s() - cpu_start_s);
  }
  MESSAGE("worst collector step over a 3 MiB heap: " << worst_s * 1e3 << " ms of CPU");
  CHECK_FALSE(script->disabled());
  CHECK(worst_s < 0.1);
}

// ---- Load --------------------------------------------------------------------------------

TEST_CASE("hostile: a top level of costly instructions stops at the load deadline") {
  ScriptLimits limits;
  limits.memory_bytes = 16u << 20;
  limits.load_time_s = 1.0;
  const auto start = std::chrono::steady_clock::now();
  const std::string error = script_load_error(
      "local t = {}\n"
      "for i = 1, 100000 do t[i * 7 + 0.5] = true end\n"
      "for i = 1, 99999 do t[i * 7 + 0.5] = nil end\n"
      "while true do next(t) end\n",
      {}, limits);
  const double elapsed_s = seconds_since(start);
  MESSAGE("sparse next() at load until the deadline: " << elapsed_s * 1e3 << " ms");
  CHECK(error == "t.lua:4: load time limit exceeded (1 s to load the script)");
  CHECK(elapsed_s < 5.0);
  check_engine_still_works();
}

TEST_CASE("hostile: load_time is a key of an effect's limits") {
  const auto parse = [](const nlohmann::json& limits) {
    ObjectReader reader(limits, "/effects/0/limits", "test.json");
    return parse_script_limits(reader);
  };
  CHECK(parse(nlohmann::json::object()).load_time_s == 5.0);
  CHECK(parse({{"load_time", "250 ms"}}).load_time_s == doctest::Approx(0.25));
  CHECK_THROWS_WITH_AS(parse({{"load_time", "700 s"}}),
                       doctest::Contains("/effects/0/limits/load_time: must be at most 600 s"),
                       InputError);
  CHECK_THROWS_AS(parse({{"load_time", 0}}), InputError);
}

TEST_CASE("hostile: the compile itself stops at the load deadline") {
  // 200 000 distinct string constants: the compiler allocates for each, which is where
  // the deadline is checked (no hook runs while Lua compiles).
  std::string source;
  for (int i = 0; i < 200000; ++i) source += "x = 'constant" + std::to_string(i) + "'\n";
  source += "function force(s) return 0 end\n";
  ScriptLimits limits;
  limits.memory_bytes = 1u << 30;
  limits.load_time_s = 0.005;
  const auto start = std::chrono::steady_clock::now();
  const std::string error = script_load_error(source, {}, limits);
  const double elapsed_s = seconds_since(start);
  CHECK(error == "t.lua: load time limit exceeded (0.005 s to load the script)");
  CHECK(elapsed_s < 2.0);
}

TEST_CASE("hostile: a source of many number literals is refused before Lua compiles it") {
  // 16 000 integers that all collide in the compiler's constant table (modulus 2^14 - 1):
  // Lua took about 1 s to compile them, without one allocation for the deadline to see.
  std::string numbers = "local t = {";
  for (int i = 1; i <= 16000; ++i) numbers += std::to_string(16383 * i) + ",";
  numbers += "}\nfunction force(s) return 0 end\n";
  const auto start = std::chrono::steady_clock::now();
  CHECK(script_load_error(numbers) ==
        "t.lua: 16001 number literals; a script may have at most 10000 (compiling many numbers "
        "can take seconds): compute large tables in code");
  CHECK(seconds_since(start) < 0.5);
  // Numbers in names, strings and comments do not count; 10 000 literals are fine.
  std::string fine = "local t = {";
  for (int i = 1; i <= 9997; ++i) fine += "1,";
  fine += "}\nlocal s1 = '123 456' -- 789 1011\n--[==[ 1 2 3 ]==] local s2 = [[4 5 6]]\n"
          "function force(s) return #t + 0x1p4 + 1e-3 - 16.001 end\n";
  CHECK(script_load_error(fine) == "");
}

TEST_CASE("hostile: params are checked in one pass over the source, however many there are") {
  // 20 000 params in a 500 KB source: locating each declaration used to scan the source,
  // so 5 times the params took 25 times as long. Judged by how the CPU time of the load
  // grows (not by a time limit, which a sanitizer build on a loaded machine can pass).
  const auto load_cpu_s = [](int count) {
    std::string source = "params = {\n";
    for (int i = 0; i < count; ++i) source += "  p" + std::to_string(i) + " = \"" + std::to_string(i) + " mm\",\n";
    source += "}\nfunction force(s) return params.p" + std::to_string(count - 1) + " end\n";
    nlohmann::json overrides = nlohmann::json::object();
    for (int i = 0; i < count; i += 2) overrides["p" + std::to_string(i)] = "1 mm";
    ScriptLimits limits;
    limits.memory_bytes = 64u << 20;
    const double start_s = thread_cpu_s();
    CHECK(script_load_error(source, overrides, limits) == "");
    return thread_cpu_s() - start_s;
  };
  load_cpu_s(4000);  // warm up the allocator and caches
  const double small_s = load_cpu_s(4000);
  const double large_s = load_cpu_s(20000);
  MESSAGE("load of 4000 params: " << small_s * 1e3 << " ms of CPU, of 20 000: " << large_s * 1e3 << " ms");
  // Linear in the source, n log n in the overrides: measured 7 to 8 times; quadratic: 25.
  CHECK(large_s < 14.0 * small_s);
  // A bad default still names its line.
  CHECK(script_load_error("params = {\n  a = \"1 mm\",\n  b = \"2 mmm\",\n}\nfunction force(s) return 0 end")
            .find("t.lua:3: params.b:") == 0);
}

}  // namespace
}  // namespace hapscene::HAPSCENE_TEST_FILE
