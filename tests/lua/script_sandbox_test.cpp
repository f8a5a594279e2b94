// The sandbox: escapes are refused at load with a message naming the line; what remains
// works, and cannot be used to change the host or another script.
#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;
using test::compile_inline;
using test::kProbeSuffix;
using test::script_load_error;
using test::run_inline;

TEST_CASE("sandbox: io, os, debug, package and the loaders are not there") {
  for (const char* name : {"io", "os", "debug", "package", "require", "load", "loadstring",
                           "dofile", "loadfile"}) {
    CAPTURE(name);
    CHECK(script_load_error(std::string("local escape = ") + name + "\nfunction force(s) return 0 end",
                     {}, {}, "scripts/escape.lua") ==
          std::string("scripts/escape.lua:1: undefined global '") + name +
              "' (scripts run in a sandbox without it; see docs/reference/lua.md)");
  }
  CHECK(script_load_error("os.execute('echo hacked')") ==
        "t.lua:1: undefined global 'os' (scripts run in a sandbox without it; see "
        "docs/reference/lua.md)");
  CHECK(script_load_error("local f = io.open('/etc/passwd')") ==
        "t.lua:1: undefined global 'io' (scripts run in a sandbox without it; see "
        "docs/reference/lua.md)");
  // Raw access does not find them either.
  CHECK(script_load_error("assert(rawget(_G, 'load') == nil and rawget(_G, 'require') == nil)\n"
                   "function force(s) return 0 end") == "");
}

TEST_CASE("sandbox: string.dump, string patterns and binary chunks are refused") {
  CHECK(script_load_error("local dump = string.dump") == "t.lua:1: string.dump is not available in scripts");
  CHECK(script_load_error("local n = ('aaa'):find('a*b')") ==
        "t.lua:1: string.find is not available in scripts (a string pattern can run for seconds "
        "inside one call, where the budget cannot stop it)");
  CHECK(script_load_error("local r = string.gsub('x', 'x', 'y')") ==
        "t.lua:1: string.gsub is not available in scripts (a string pattern can run for seconds "
        "inside one call, where the budget cannot stop it)");
  // A precompiled chunk would skip the parser's checks: only text is loaded.
  CHECK(script_load_error(std::string("\x1bLuaT\x00\x19\x93\r\n\x1a\n", 12)) ==
        "t.lua: attempt to load a binary chunk (mode is 't')");
}

TEST_CASE("sandbox: finalizers cannot be set, so none runs outside the budget") {
  CHECK(script_load_error("local t = setmetatable({}, { __gc = function() while true do end end })") ==
        "t.lua:1: setmetatable: __gc finalizers are not allowed in scripts (they would run "
        "outside the instruction budget)");
  // Adding __gc after setmetatable does not register a finalizer (Lua semantics), so the
  // collection at the end of loading does not run it.
  auto script = run_inline(
      "ran = false\n"
      "do local mt = {}; local t = setmetatable({}, mt); mt.__gc = function() ran = true end end\n"
      "function force(s) return ran and 1 or 0 end");
  script->collect_garbage(1000);
  CHECK(script->force_N(at(0.0)) == 0.0);
  CHECK_FALSE(script->disabled());
}

TEST_CASE("sandbox: the collector belongs to the host") {
  CHECK(script_load_error("collectgarbage('stop')") ==
        "t.lua:1: collectgarbage(\"stop\") is not available in scripts (the host runs the "
        "collector between ticks); only collectgarbage(\"count\") is");
  CHECK(script_load_error("collectgarbage()") ==
        "t.lua:1: collectgarbage(\"collect\") is not available in scripts (the host runs the "
        "collector between ticks); only collectgarbage(\"count\") is");
  auto script = run_inline("function force(s) return collectgarbage('count') end");
  const double kib = script->force_N(at(0.0));
  CHECK(kib > 10.0);
  CHECK(kib < 100.0);
}

TEST_CASE("sandbox: the string metatable is hidden and string methods cannot be changed") {
  CHECK(script_load_error("assert(getmetatable('') == false)\nfunction force(s) return 0 end") == "");
  CHECK(script_load_error("getmetatable('').__index = {}") ==
        "t.lua:1: attempt to index a boolean value");
  CHECK(script_load_error("setmetatable(getmetatable(''), nil)") ==
        "t.lua:1: bad argument #1 to 'setmetatable' (table expected, got boolean)");
  // Changing the string table changes neither the methods nor string arithmetic.
  CHECK(script_load_error("string.upper = function() return 'pwned' end\n"
                   "assert(('a'):upper() == 'A')\n"
                   "function force(s) return 0 end") == "");
  CHECK(script_load_error("local n = '10' + 1") ==
        "t.lua:1: attempt to perform arithmetic on a string value (constant '10')");
}

TEST_CASE("sandbox: the script's own tables are protected") {
  for (const char* table : {"_G", "params", "string", "math"}) {
    CAPTURE(table);
    CHECK(script_load_error(std::string("params = { a = 1 }\nsetmetatable(") + table + ", nil)") ==
          "t.lua:2: cannot change a protected metatable");
  }
  CHECK(script_load_error("function force(s) setmetatable(s, nil) return 0 end") ==
        std::string("t.lua:1: cannot change a protected metatable") + std::string(kProbeSuffix));
}

TEST_CASE("sandbox: reading an undefined global is an error, with a suggestion") {
  CHECK(script_load_error("stiffness = 100\nfunction force(s) return -stiffnes * s.x end") ==
        std::string("t.lua:2: undefined global 'stiffnes' (did you mean 'stiffness'?)") +
            std::string(kProbeSuffix));
  CHECK(script_load_error("local x = undefined_thing") == "t.lua:1: undefined global 'undefined_thing'");
  CHECK(script_load_error("local x = math.sinn(1)") ==
        "t.lua:1: math has no field 'sinn' (did you mean 'math.sin'?)");
}

TEST_CASE("sandbox: globals are declared while loading, new ones while running are errors") {
  // Top-level state in globals is fine and persists between calls.
  auto counter = run_inline("count = 0\nfunction force(s) count = count + 1 return count end");
  CHECK(counter->force_N(at(0.0)) == 1.0);
  CHECK(counter->force_N(at(0.0)) == 2.0);
  // A global first created inside force is a typo or per-tick garbage.
  CHECK(script_load_error("function force(s)\n  total = s.x\n  return 0\nend") ==
        std::string("t.lua:2: cannot create global 'total' while running (declare it at the top "
                    "level of the script, or use a local)") +
            std::string(kProbeSuffix));
}

TEST_CASE("sandbox: s is read-only and its fields are checked") {
  CHECK(script_load_error("function force(s) s.x = 1 return 0 end") ==
        std::string("t.lua:1: s is read-only (copy the value into a local to change it)") +
            std::string(kProbeSuffix));
  CHECK(script_load_error("function force(s) return s.xx end") ==
        std::string("t.lua:1: s has no field 'xx' (did you mean 's.x'?)") + std::string(kProbeSuffix));
  CHECK(script_load_error("function force(s) return s.position end") ==
        std::string("t.lua:1: s has no field 'position' (s has x, v, t, dt)") +
            std::string(kProbeSuffix));
  // pairs(s) sees nothing: the values live in a table the script cannot reach.
  auto script = run_inline("function force(s) local n = 0 for _ in pairs(s) do n = n + 1 end "
                           "return n + (getmetatable(s) == false and 10 or 0) end");
  CHECK(script->force_N(at(0.5)) == 10.0);
}

TEST_CASE("sandbox: what a script may use works") {
  auto script = run_inline(R"(
    -- coroutines, closures, tables, string formatting, utf8, math
    local gen = coroutine.wrap(function() for i = 1, 3 do coroutine.yield(i) end end)
    local sum = gen() + gen() + gen()
    local t = { 3, 1, 2 }
    table.sort(t)
    assert(table.concat(t, ",") == "1,2,3")
    assert(string.format("%.2f", math.pi) == "3.14")
    assert(("abc"):upper() == "ABC" and #string.rep("ab", 3, "-") == 8)
    assert(utf8.len("h\u{e9}") == 2)
    assert(select("#", table.unpack({ 1, 2, 3 })) == 3)
    assert(pcall(error, "x") == false)
    assert(math.type(1) == "integer" and tostring(nil) == "nil" and tonumber("0x10") == 16)
    function force(s) return sum end
  )");
  CHECK(script->force_N(at(0.0)) == 6.0);
}

TEST_CASE("sandbox: math.random is seeded, so runs repeat") {
  const ScriptProgram program =
      compile_inline("function force(s) return math.random() end");
  auto first = ScriptInstance::create(program);
  auto second = ScriptInstance::create(program);
  for (int i = 0; i < 5; ++i) CHECK(first->force_N(at(0.0)) == second->force_N(at(0.0)));
}

TEST_CASE("sandbox: each instance has its own state") {
  const ScriptProgram program = compile_inline(
      "count = 0\nfunction force(s) count = count + 1 string.upper = nil return count end");
  auto first = ScriptInstance::create(program);
  auto second = ScriptInstance::create(program);
  CHECK(first->force_N(at(0.0)) == 1.0);
  CHECK(first->force_N(at(0.0)) == 2.0);
  CHECK(second->force_N(at(0.0)) == 1.0);
}

}  // namespace
}  // namespace hapscene
