// Straight-line force(): a force() whose own code cannot loop runs without the
// per-instruction count hook (charged its length per call). Everything it calls in Lua,
// by any route, must still be counted and stopped by the budget.
#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;
using test::run_inline;

constexpr const char* kBudgetFault = "instruction budget exceeded (100000 instructions per call)";

std::int64_t straight_line(const char* source) {
  return run_inline(source)->force_straight_line_instructions();
}

// Loads `source` (whose force returns 0 at x <= 0), calls force at x = 1 cm and returns
// the fault message ("" when none).
std::string fault_at_1cm(const std::string& source) {
  auto script = run_inline(source);
  REQUIRE(script->force_straight_line_instructions() > 0);  // the case under test
  CHECK(script->force_N(at(0.01)) == 0.0);
  CHECK(script->disabled());
  return std::string(script->fault_message());
}

TEST_CASE("straight line: loop-free force functions are recognised, loops of every kind are not") {
  CHECK(straight_line("function force(s) return -100 * s.x end") > 0);
  CHECK(straight_line("function force(s) if s.x > 0 then return -1 end return 0 end") > 0);
  CHECK(straight_line("local function f(x) while true do end end\n"
                      "function force(s) return 0 end") > 0);  // a loop elsewhere is not force's
  CHECK(straight_line("function force(s) while s.x > 1 do end return 0 end") == 0);
  CHECK(straight_line("function force(s) repeat until s.x < 1 return 0 end") == 0);
  CHECK(straight_line("function force(s) for i = 1, 2 do end return 0 end") == 0);
  CHECK(straight_line("function force(s) for k in pairs({}) do end return 0 end") == 0);
  CHECK(straight_line("function force(s)\n ::again::\n if s.x > 1 then goto again end\n return 0\nend") == 0);
  CHECK(straight_line("force = rawlen") == 0);  // a C function (0 for the empty proxy): counted as before
  // The length is the function's instruction count: a longer body is longer.
  CHECK(straight_line("function force(s) local a = s.x + 1 local b = a * 2 return b - a end") >
        straight_line("function force(s) return s.x end"));
}

TEST_CASE("straight line: what force calls is counted, whichever way it is called") {
  const std::string tail = "\n  return 0\nend";
  const std::string guard = "function force(s)\n  if s.x <= 0 then return 0 end\n";
  SUBCASE("a local Lua function") {
    CHECK(fault_at_1cm("local function spin() while true do end end\n" + guard + "  spin()" + tail) ==
          std::string("t.lua:1: ") + kBudgetFault);
  }
  SUBCASE("a tail call") {
    CHECK(fault_at_1cm("local function spin() while true do end end\n" + guard + "  return spin()\nend") ==
          std::string("t.lua:1: ") + kBudgetFault);
  }
  SUBCASE("an arithmetic metamethod") {
    CHECK(fault_at_1cm("local m = setmetatable({}, {__add = function() while true do end end})\n" + guard +
                       "  local x = m + 1" + tail) == std::string("t.lua:1: ") + kBudgetFault);
  }
  SUBCASE("an __index function") {
    CHECK(fault_at_1cm("local m = setmetatable({}, {__index = function() while true do end end})\n" + guard +
                       "  local x = m.anything" + tail) == std::string("t.lua:1: ") + kBudgetFault);
  }
  SUBCASE("a comparison metamethod") {
    CHECK(fault_at_1cm("local mt = {__lt = function() while true do end end}\n"
                       "local a, b = setmetatable({}, mt), setmetatable({}, mt)\n" + guard +
                       "  local x = a < b" + tail) == std::string("t.lua:1: ") + kBudgetFault);
  }
  SUBCASE("pcall of a Lua function (the stop cannot be caught)") {
    CHECK(fault_at_1cm(guard + "  pcall(function() while true do end end)" + tail) ==
          std::string("t.lua:3: ") + kBudgetFault);
  }
  SUBCASE("a Lua function called from a C function (table.sort's comparator)") {
    CHECK(fault_at_1cm(guard + "  table.sort({3, 2, 1}, function(a, b) while true do end end)" + tail) ==
          std::string("t.lua:3: ") + kBudgetFault);
  }
  SUBCASE("tostring with a __tostring metamethod") {
    CHECK(fault_at_1cm("local m = setmetatable({}, {__tostring = function() while true do end end})\n" + guard +
                       "  local text = tostring(m)" + tail) == std::string("t.lua:1: ") + kBudgetFault);
  }
  SUBCASE("a coroutine created in an earlier call, resumed later") {
    auto script = run_inline(
        "local co\n"
        "function force(s)\n"
        "  if s.x <= 0 then return 0 end\n"
        "  if co == nil then co = coroutine.create(function() coroutine.yield() while true do end end) end\n"
        "  coroutine.resume(co)\n"
        "  return 1\n"
        "end");
    REQUIRE(script->force_straight_line_instructions() > 0);
    CHECK(script->force_N(at(0.01)) == 1.0);  // runs up to the yield
    CHECK_FALSE(script->disabled());
    CHECK(script->force_N(at(0.01)) == 0.0);  // the loop, counted on the coroutine's thread
    CHECK(script->disabled());
    CHECK(std::string(script->fault_message()).find(kBudgetFault) != std::string::npos);
  }
}

TEST_CASE("straight line: calls into C functions do not switch counting on, and results stay exact") {
  // math.floor and friends are C functions: the call stays unhooked and the result is the
  // same as the formula.
  auto script = run_inline(
      "function force(s)\n"
      "  return -100 * (s.x - math.floor(s.x * 100) / 100) + math.abs(s.x) * 0\n"
      "end");
  REQUIRE(script->force_straight_line_instructions() > 0);
  for (int i = 0; i < 1000; ++i) {
    const double x_m = -0.05 + 1e-4 * i;
    REQUIRE(script->force_N(at(x_m)) == -100 * (x_m - std::floor(x_m * 100) / 100) + std::abs(x_m) * 0);
  }
  CHECK_FALSE(script->disabled());
}

TEST_CASE("straight line: a body longer than the budget is counted instruction by instruction") {
  ScriptLimits limits;
  limits.instructions_per_call = 100;
  std::string body = "function force(s)\n  local a = s.x\n";
  for (int i = 0; i < 120; ++i) body += "  a = a + 1\n";
  body += "  return 0\nend";
  auto script = ScriptInstance::create(test::compile_inline(body, {}));
  CHECK(script->force_straight_line_instructions() > 100);
  CHECK_THROWS_WITH_AS(test::compile_inline(body, limits),
                       doctest::Contains("instruction budget exceeded (100 instructions per call)"),
                       InputError);
}

}  // namespace
}  // namespace hapscene
