// The cheap path of force(s): a loop-free force that calls nothing runs with no hook at
// all while no metatable of the script holds a function, and a force that only reads
// fields of s gets the table of values itself instead of the read-only proxy. The
// sandbox's promises stay: nothing unbounded runs uncounted, s cannot be written, and an
// unknown field of s is an error with the same message.
#include "tests/lua/script_test_support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using test::at;
using test::script_load_error;
using test::run_inline;

constexpr const char* kBudgetFault = "instruction budget exceeded (100000 instructions per call)";

TEST_CASE("fast call: the shipped spring and texture run unhooked and read s directly") {
  for (const char* name : {"spring.lua", "texture.lua"}) {
    CAPTURE(name);
    auto script = ScriptInstance::create(test::compile_shipped(name));
    CHECK(script->force_runs_without_hooks());
    CHECK(script->force_reads_state_directly());
  }
  auto spring = ScriptInstance::create(test::compile_shipped("spring.lua"));
  CHECK(spring->force_N(at(0.01)) == doctest::Approx(-1.0));
}

TEST_CASE("fast call: what keeps the hook") {
  const auto unhooked = [](const char* source) { return run_inline(source)->force_runs_without_hooks(); };
  CHECK(unhooked("function force(s) if s.x > 0 then return -1 end return 0 end"));
  CHECK_FALSE(unhooked("function force(s) return math.abs(s.x) end"));         // a call
  CHECK_FALSE(unhooked("local function f() return 1 end\nfunction force(s) return f() end"));  // a tail call
  CHECK_FALSE(unhooked("function force(s) while s.x > 1 do end return 0 end"));  // a loop
  // A metatable holding a function, set anywhere in the script, reaches code with no call
  // instruction (an operator); a table-valued __index does not.
  CHECK_FALSE(unhooked("local m = setmetatable({}, {__add = function() return 1 end})\n"
                       "function force(s) return 0 end"));
  CHECK(unhooked("local m = setmetatable({}, {__index = {a = 1}})\nfunction force(s) return m.a end"));
}

TEST_CASE("fast call: a metamethod set after load switches counting on") {
  auto script = run_inline(
      "local m = {}\n"
      "function reset() setmetatable(m, {__add = function() while true do end end}) end\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  local y = m + 1\n"
      "  return 0\n"
      "end");
  CHECK(script->force_runs_without_hooks());
  CHECK(script->force_N(at(0.0)) == 0.0);
  script->reset();
  CHECK_FALSE(script->force_runs_without_hooks());
  CHECK(script->force_N(at(0.01)) == 0.0);
  CHECK(script->disabled());
  CHECK(std::string(script->fault_message()) == std::string("t.lua:2: ") + kBudgetFault);
}

TEST_CASE("fast call: a C function as a metamethod that calls script code is counted") {
  // `spin + m` runs m's __add, pcall, which calls spin: no call instruction in force.
  auto script = run_inline(
      "local spin = function() while true do end end\n"
      "local m = setmetatable({}, {__add = pcall})\n"
      "function force(s)\n"
      "  if s.x <= 0 then return 0 end\n"
      "  local y = spin + m\n"
      "  return 0\n"
      "end");
  CHECK_FALSE(script->force_runs_without_hooks());
  CHECK(script->force_N(at(0.01)) == 0.0);
  CHECK(script->disabled());
  CHECK(std::string(script->fault_message()).find(kBudgetFault) != std::string::npos);
}

TEST_CASE("fast call: s is passed directly only when force reads nothing but its fields") {
  const auto direct = [](const char* source) { return run_inline(source)->force_reads_state_directly(); };
  CHECK(direct("function force(s) return -100 * s.x end"));
  CHECK(direct("function force(s) local a = s.x for i = 1, 3 do a = a + s.dt end return a end"));
  CHECK_FALSE(direct("function force(s) local q = s return q.x end"));                // copied
  CHECK_FALSE(direct("function force(s) return rawlen(s) end"));                      // passed
  CHECK_FALSE(direct("saved = false\nfunction reset() saved = false end\n"
                     "function force(s) return (s == saved) and 1 or 0 end"));         // compared
  CHECK_FALSE(direct("function force(s) local f = function() return s.x end return 0 end"));  // captured
  CHECK_FALSE(direct("function force(s) local k = \"x\" return s[k] end"));            // other reads
  CHECK_FALSE(direct("function force(...) local s = ... return s.x end"));            // varargs
  CHECK_FALSE(direct("function force(s) s = {x = 1} return s.x end"));                // overwritten
  // Writes keep the proxy, so they are still errors at the write.
  CHECK(script_load_error("function force(s) s.x = 1 return 0 end").starts_with(
      "t.lua:1: s is read-only (copy the value into a local to change it)"));
  CHECK(script_load_error("function force(s) s.dt = s.x return 0 end").starts_with("t.lua:1: s is read-only"));
  // An unknown field: the same error and hint either way.
  CHECK(script_load_error("function force(s) return s.xx end").starts_with(
      "t.lua:1: s has no field 'xx' (did you mean 's.x'?)"));
}

TEST_CASE("fast call: a directly read s still hides what needs leaves out") {
  auto script = run_inline("needs = {velocity = false}\nfunction force(s) if s.x > 0 then return s.v end return 0 end");
  REQUIRE(script->force_reads_state_directly());
  CHECK(script->force_N(at(0.01)) == 0.0);
  CHECK(std::string(script->fault_message()).find("s.v is not available") != std::string::npos);
}

TEST_CASE("fast call: warming a script changes nothing it computes and allocates nothing") {
  auto warmed = ScriptInstance::create(test::compile_shipped("spring.lua"));
  auto plain = ScriptInstance::create(test::compile_shipped("spring.lua"));
  warmed->warm();  // before any call: the hook mode is not known yet, so it does nothing
  for (int i = 0; i < 100; ++i) {
    const double x_m = -0.03 + 6e-4 * i;
    const std::uint64_t allocations = warmed->allocation_count();
    warmed->warm();
    CHECK(warmed->allocation_count() == allocations);
    CHECK(warmed->force_N(at(x_m)) == plain->force_N(at(x_m)));
  }
  CHECK_FALSE(warmed->disabled());
}

}  // namespace
}  // namespace hapscene::HAPSCENE_TEST_FILE
