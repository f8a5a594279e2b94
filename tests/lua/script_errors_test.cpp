// Errors: load-time problems are InputErrors naming file and line; a runtime error or a
// bad return value disables the script (0 N from then on) and is reported once.
#include <algorithm>

#include "tests/lua/script_test_support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using test::at;
using test::compile_inline;
using test::kProbeSuffix;
using test::script_load_error;
using test::run_inline;

TEST_CASE("errors: a syntax error names the file and line") {
  CHECK(script_load_error("params = { height = \"2 mm\" }\n\nx = = 1\n", {}, {}, "scripts/bumps.lua") ==
        "scripts/bumps.lua:3: unexpected symbol near '='");
  CHECK(script_load_error("function force(s)\n  return 1", {}, {}, "scripts/bumps.lua") ==
        "scripts/bumps.lua:2: 'end' expected (to close 'function' at line 1) near <eof>");
}

TEST_CASE("errors: an error in top-level code fails the load") {
  CHECK(script_load_error("local a = 1\nerror('boom')") == "t.lua:2: boom");
  CHECK(script_load_error("error('no place', 0)") == "t.lua: no place");
  CHECK(script_load_error("error({})") == "t.lua: error while loading (error object is a table value)");
}

TEST_CASE("errors: force must be a function, reset and needs are checked") {
  CHECK(script_load_error("local function force(s) return 0 end") ==
        "t.lua: the script must define a global function force(s) that returns the force in N");
  CHECK(script_load_error("force = 3") == "t.lua: force must be a function, got a number");
  CHECK(script_load_error("function force(s) return 0 end\nreset = true") ==
        "t.lua: reset must be a function, got a boolean");
  CHECK(script_load_error("needs = { velocty = false }\nfunction force(s) return 0 end") ==
        "t.lua: needs.velocty: unknown need (did you mean \"velocity\"?) (a script can declare "
        "velocity and time)");
  CHECK(script_load_error("needs = { velocity = 0 }\nfunction force(s) return 0 end") ==
        "t.lua: needs.velocity: expected true or false, got a number");
  CHECK(script_load_error("needs = 'none'\nfunction force(s) return 0 end") ==
        "t.lua: needs must be a table such as { velocity = false }, got a string");
}

TEST_CASE("errors: needs declares what s carries") {
  const ScriptProgram both = compile_inline("function force(s) return s.v + s.t end");
  CHECK(both.needs_velocity);
  CHECK(both.needs_time);
  const ScriptProgram neither =
      compile_inline("needs = { velocity = false, time = false }\nfunction force(s) return s.x end");
  CHECK_FALSE(neither.needs_velocity);
  CHECK_FALSE(neither.needs_time);
  // Reading what was declared unneeded is caught at load by the check call.
  CHECK(script_load_error("needs = { velocity = false }\nfunction force(s) return -s.v end") ==
        std::string("t.lua:2: s.v is not available: the script declares needs.velocity = false") +
            std::string(kProbeSuffix));
  CHECK(script_load_error("needs = { time = false }\nfunction force(s) return s.t end") ==
        std::string("t.lua:2: s.t is not available: the script declares needs.time = false") +
            std::string(kProbeSuffix));
}

TEST_CASE("errors: a runtime error disables the script, reported once with its line") {
  auto script = run_inline(
      "function force(s)\n"
      "  if s.x > 0.02 then\n"
      "    local gain = nil\n"
      "    return gain * s.x\n"
      "  end\n"
      "  return -10 * s.x\n"
      "end");
  CHECK(script->force_N(at(0.01, 0.0, 1.0)) == -0.1);
  CHECK(script->fault_message().empty());
  CHECK(script->fault() == ScriptFault::none);
  CHECK(script->force_N(at(0.03, 0.0, 1.5)) == 0.0);
  CHECK(script->disabled());
  CHECK(script->fault_message() == "t.lua:4: attempt to perform arithmetic on a nil value (local 'gain')");
  CHECK(script->fault() == ScriptFault::error);
  CHECK(script->fault_count() == 1);
  CHECK(script->fault_time_s() == 1.5);
  // From then on: 0 N, the same single fault.
  CHECK(script->force_N(at(0.01)) == 0.0);
  CHECK(script->fault_count() == 1);
}

TEST_CASE("errors: the return value must be a finite number") {
  struct Case {
    const char* returned;
    const char* message;
  };
  for (const Case& c : {Case{"nil", "t.lua:1: force(s) returned nil, expected a finite number (N)"},
                        Case{"'1.5'", "t.lua:1: force(s) returned string, expected a finite number (N)"},
                        Case{"{}", "t.lua:1: force(s) returned table, expected a finite number (N)"},
                        Case{"true", "t.lua:1: force(s) returned boolean, expected a finite number (N)"},
                        Case{"0/0", "t.lua:1: force(s) returned nan, expected a finite number (N)"},
                        Case{"1/0", "t.lua:1: force(s) returned inf, expected a finite number (N)"},
                        Case{"-1/0", "t.lua:1: force(s) returned -inf, expected a finite number (N)"}}) {
    CAPTURE(c.returned);
    auto script = run_inline(std::string("function force(s) if s.x > 0 then return ") + c.returned +
                             " end return 0 end");
    CHECK(script->force_N(at(0.01)) == 0.0);
    CHECK(script->disabled());
    CHECK(script->fault_message() == c.message);
    CHECK(script->fault() == ScriptFault::bad_return);
  }
  // Integers are numbers too.
  auto integer = run_inline("function force(s) return 2 end");
  CHECK(integer->force_N(at(0.0)) == 2.0);
}

TEST_CASE("errors: error values that are not strings, or carry no position") {
  auto table = run_inline("function force(s) if s.x > 0 then error({ code = 1 }) end return 0 end");
  table->force_N(at(0.01));
  CHECK(table->fault_message() == "t.lua: error in force(s) (error object is a table value)");
  auto bare = run_inline("function force(s) if s.x > 0 then error('too far', 0) end return 0 end");
  bare->force_N(at(0.01));
  CHECK(bare->fault_message() == "t.lua: too far");
}

TEST_CASE("errors: an error in reset() disables the script") {
  CHECK(script_load_error("function reset() error('cannot reset') end\nfunction force(s) return 0 end") ==
        "t.lua:1: cannot reset (while checking reset() at load)");
  auto script = run_inline(
      "calls = 0\n"
      "function reset() calls = calls + 1 if calls > 1 then error('second reset') end end\n"
      "function force(s) return calls end");
  script->reset();
  CHECK(script->force_N(at(0.0)) == 1.0);
  script->reset();
  CHECK(script->disabled());
  CHECK(script->fault_message() == "t.lua:2: second reset");
  CHECK(script->force_N(at(0.0)) == 0.0);
}

TEST_CASE("errors: a broken reload leaves the running instance alone") {
  auto running = run_inline("function force(s) return -100 * s.x end");
  CHECK(running->force_N(at(0.01)) == -1.0);
  CHECK(script_load_error("function force(s) return -100 * s.x") ==
        "t.lua:1: 'end' expected near <eof>");
  CHECK(running->force_N(at(0.02)) == -2.0);
  CHECK_FALSE(running->disabled());
}

TEST_CASE("errors: a fault in one run does not touch another run of the same program") {
  const ScriptProgram program =
      compile_inline("function force(s) if s.x > 0.02 then error('too far') end return 1 end");
  auto first = ScriptInstance::create(program);
  auto second = ScriptInstance::create(program);
  CHECK(first->force_N(at(0.03)) == 0.0);
  CHECK(first->disabled());
  CHECK(second->force_N(at(0.01)) == 1.0);
  CHECK_FALSE(second->disabled());
}

TEST_CASE("errors: a script's own checks of its params read as load errors") {
  // The line of the script's error() call.
  const std::string text = test::read_script("texture.lua");
  const std::size_t at_call = text.find("error(\"texture:");
  REQUIRE(at_call != std::string::npos);
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at_call), '\n');
  try {
    test::compile_shipped("texture.lua", {{"width", "0 mm"}});
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == "scripts/texture.lua:" + std::to_string(line) +
                                       ": texture: width must be positive and gap must not be "
                                       "negative");
  }
}

}  // namespace
}  // namespace hapscene::HAPSCENE_TEST_FILE
