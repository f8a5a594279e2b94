// The dry run of the real-time loop's warming (ScriptInstance::begin_dry_run, warm): in
// the VM, a force that only reads is called again only with exactly the input of its last
// call, which succeeded; anything else answers 0 N and changes nothing. A translated force
// (force_program.hpp) has no side effects at all and runs on any input. The VM cases turn
// the translation off (`in_vm`), since the shipped spring and these small forces would
// otherwise run translated.
#include <cmath>

#include "tests/lua/script_test_support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using test::at;
using test::run_inline;

// Tells 0.0 from -0.0 (1 / x is inf or -inf).
constexpr const char* kSignOfZero =
    "needs = {velocity = false, time = false}\n"
    "function force(s) if 1 / s.x > 0 then return 1 end return -1 end";

ScriptLimits in_vm() {
  ScriptLimits limits;
  limits.translate_force = false;
  return limits;
}

ScriptProgram shipped_in_vm(const char* name) {
  ScriptProgram program = test::compile_shipped(name);
  program.limits.translate_force = false;
  return program;
}

TEST_CASE("dry run: the last call again, only with the same input") {
  auto script = ScriptInstance::create(shipped_in_vm("spring.lua"));
  // Before any call s holds no call's input: nothing is called.
  script->begin_dry_run();
  CHECK(script->force_N(at(0.0)) == 0.0);
  script->end_dry_run();
  CHECK(script->dry_calls() == 0);

  const double force_N = script->force_N(at(0.01, 0.0, 0.5));
  CHECK(force_N == doctest::Approx(-1.0));
  script->begin_dry_run();
  CHECK(script->force_N(at(0.01, 0.0, 0.5)) == force_N);  // repeated through force_N
  CHECK(script->dry_calls() == 1);
  // Another input is not run (warm() runs the last call instead) and answers 0 N.
  CHECK(script->force_N(at(0.02, 0.0, 0.5)) == 0.0);
  CHECK(script->force_N(at(0.01, 0.0, 0.501)) == 0.0);  // another time
  CHECK(script->force_N(at(0.01, 0.0, 0.5, 0.002)) == 0.0);  // another period
  script->end_dry_run();
  // The next real call is what it would have been.
  auto plain = ScriptInstance::create(shipped_in_vm("spring.lua"));
  CHECK(script->force_N(at(0.02)) == plain->force_N(at(0.02)));
  CHECK_FALSE(script->disabled());
}

TEST_CASE("dry run: the same input means the same bits") {
  auto script = run_inline(kSignOfZero, in_vm());
  CHECK(script->force_N(at(0.0)) == 1.0);
  script->begin_dry_run();
  CHECK(script->force_N(at(-0.0)) == 0.0);  // not repeated: -0.0 would change s.x
  CHECK(script->force_N(at(0.0)) == 1.0);   // repeated
  script->end_dry_run();
  CHECK(script->force_N(at(-0.0)) == -1.0);
}

TEST_CASE("dry run: a disabled script counts no skipped call, a stateful one is not called") {
  auto faulty = run_inline("function force(s) if s.x > 0 then return nil end return 0 end");
  CHECK(faulty->force_N(at(0.01)) == 0.0);
  REQUIRE(faulty->disabled());
  const std::uint64_t skipped = faulty->skipped_calls();
  faulty->begin_dry_run();
  CHECK(faulty->force_N(at(0.01)) == 0.0);
  faulty->end_dry_run();
  faulty->warm();
  CHECK(faulty->skipped_calls() == skipped);
  CHECK(faulty->dry_calls() == 0);

  auto counter = run_inline("needs = {velocity = false, time = false}\nlocal n = 0\nfunction force(s) n = n + 1 return n end");
  CHECK(counter->force_runs_without_hooks());
  CHECK(counter->force_N(at(0.0)) == 1.0);
  counter->begin_dry_run();
  CHECK(counter->force_N(at(0.0)) == 0.0);
  counter->end_dry_run();
  counter->warm();
  CHECK(counter->dry_calls() == 0);
  CHECK(counter->force_N(at(0.0)) == 2.0);
}

TEST_CASE("dry run: what counts as only reading") {
  // After one call at rest, warm() calls force again only when its code only reads.
  const auto called_again = [](const char* source) {
    auto script = run_inline(source, in_vm());
    script->force_N(at(0.0));
    script->warm();
    return script->dry_calls() == 1;
  };
  CHECK(called_again("function force(s) return -s.x end"));
  CHECK(called_again("local k = 2\nfunction force(s) if s.x > 1 and s.v < 0 or s.t == 0 then return k end return #'ab' end"));
  CHECK(called_again("local t = {1, n = 2}\nfunction force(s) return t[1] + t.n end"));
  CHECK_FALSE(called_again("local n = 0\nfunction force(s) n = s.x return 0 end"));            // an upvalue
  CHECK_FALSE(called_again("local t = {}\nfunction force(s) t[1] = s.x return 0 end"));         // a table
  CHECK_FALSE(called_again("local t = {}\nfunction force(s) t.x = s.x return 0 end"));
  CHECK_FALSE(called_again("g = 0\nfunction force(s) g = 1 return 0 end"));                   // a global
  CHECK_FALSE(called_again("function force(s) local t = {} return 0 end"));                   // a table made
  CHECK_FALSE(called_again("function force(s) local f = function() end return 0 end"));      // a closure made
  CHECK_FALSE(called_again("function force(s) local m = 'a' .. s.x return 0 end"));           // a string made
  CHECK_FALSE(called_again("function force(s, ...) return 0 end"));                           // varargs
  CHECK_FALSE(called_again("function force(s) return math.abs(s.x) end"));                   // a call (hooked)
  CHECK_FALSE(called_again("function force(s) local f = 0 for i = 1, 2 do f = f + i end return f end"));  // a loop
}

TEST_CASE("dry run: a translated force runs on any input, changes nothing, and is counted") {
  auto script = ScriptInstance::create(test::compile_shipped("spring.lua"));
  REQUIRE(script->force_translated());
  auto plain = ScriptInstance::create(test::compile_shipped("spring.lua"));
  CHECK(script->force_N(at(0.01)) == plain->force_N(at(0.01)));
  script->begin_dry_run();
  CHECK(script->force_N(at(0.02, 0.0, 0.7)) == plain->force_N(at(0.02, 0.0, 0.7)));  // any input, the same bits
  script->end_dry_run();
  script->warm();
  CHECK(script->dry_calls() == 2);
  CHECK(script->force_N(at(-0.005)) == plain->force_N(at(-0.005)));
  // A result that is not a finite number is 0 N in a dry run: the VM is not asked, no fault.
  auto nan_beyond = run_inline("function force(s) if s.x > 0.02 then return 0 / 0 end return -s.x end");
  REQUIRE(nan_beyond->force_translated());
  nan_beyond->begin_dry_run();
  CHECK(nan_beyond->force_N(at(0.03)) == 0.0);
  nan_beyond->end_dry_run();
  CHECK_FALSE(nan_beyond->disabled());
  CHECK(nan_beyond->force_N(at(0.01)) == -0.01);
}

}  // namespace
}  // namespace hapscene::HAPSCENE_TEST_FILE
