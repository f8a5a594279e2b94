// A force(s) that is straight-line arithmetic on numbers runs from a translation of its
// bytecode, not the VM: the same results to the bit, the same faults with the same
// messages, and the VM again whenever the translation's assumptions may no longer hold.
// Every comparison here is against a second instance of the same script with the
// translation turned off (the real Lua VM).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;

std::uint64_t bits(double value) {
  std::uint64_t out = 0;
  std::memcpy(&out, &value, sizeof out);
  return out;
}

// Inputs that reach every branch of the formulas below: signs, zeros, both zeros, tiny
// and huge values, and the non-finite ones the VM must report.
std::vector<double> probe_values() {
  std::vector<double> out = {0.0, -0.0, 1.0, -1.0, 0.5, -2.5, 0.0049, 0.0051, 0.01, -0.01, 1e-300,
                             1e300, -1e300, 3.0, 7.0, 1e-3, 0.0125};
  std::mt19937_64 random(1234);
  std::uniform_real_distribution<double> span(-0.05, 0.05);
  for (int i = 0; i < 40; ++i) out.push_back(span(random));
  return out;
}

// Runs the same inputs through a translated and a VM-only instance of one program and
// checks every result bit, the disabled state and the fault message after every call.
void check_same_1d(const ScriptProgram& program) {
  ScriptProgram vm_program = program;
  vm_program.limits.translate_force = false;
  auto translated = ScriptInstance::create(program);
  auto vm = ScriptInstance::create(vm_program);
  translated->reset();
  vm->reset();
  const auto values = probe_values();
  double t_s = 0.0;
  for (std::size_t i = 0; i < values.size() * 3; ++i) {
    const double x = values[i % values.size()];
    const double v = values[(i * 7 + 3) % values.size()];
    t_s += 0.001;
    const auto input = at(x, v, t_s, i % 50 == 49 ? 0.002 : 0.001);
    const double a = translated->force_N(input);
    const double b = vm->force_N(input);
    CAPTURE(x);
    CAPTURE(v);
    REQUIRE(bits(a) == bits(b));
    REQUIRE(translated->disabled() == vm->disabled());
    REQUIRE(std::string(translated->fault_message()) == std::string(vm->fault_message()));
    if (vm->disabled()) break;
  }
}

void check_same_2d(const ScriptProgram& program) {
  ScriptProgram vm_program = program;
  vm_program.limits.translate_force = false;
  auto translated = ScriptInstance::create(program);
  auto vm = ScriptInstance::create(vm_program);
  translated->reset();
  vm->reset();
  const auto values = probe_values();
  for (std::size_t i = 0; i < values.size() * 3; ++i) {
    PlanarScriptInput input;
    input.x_m = Vec2{{values[i % values.size()], 0.12 + values[(i * 5 + 1) % values.size()]}};
    input.v_m_per_s = Vec2{{values[(i * 7 + 3) % values.size()], values[(i * 11 + 2) % values.size()]}};
    input.t_s = 0.001 * static_cast<double>(i);
    input.dt_s = 0.001;
    const Vec2 a = translated->force_N(input);
    const Vec2 b = vm->force_N(input);
    REQUIRE(bits(a[0]) == bits(b[0]));
    REQUIRE(bits(a[1]) == bits(b[1]));
    REQUIRE(translated->disabled() == vm->disabled());
    REQUIRE(std::string(translated->fault_message()) == std::string(vm->fault_message()));
    if (vm->disabled()) break;
  }
}

ScriptProgram compile_planar(const std::string& name, const std::string& source) {
  return compile_script(name, source, nlohmann::json::object(), "environments/planar/t.json", "/effects/0/params",
                        {}, 2);
}

TEST_CASE("force translation: the shipped spring and texture run without the VM, to the bit") {
  for (const char* name : {"spring.lua", "texture.lua"}) {
    CAPTURE(name);
    const ScriptProgram program = test::compile_shipped(name);
    CHECK(ScriptInstance::create(program)->force_translated());
    ScriptProgram vm_program = program;
    vm_program.limits.translate_force = false;
    CHECK_FALSE(ScriptInstance::create(vm_program)->force_translated());
    check_same_1d(program);
  }
}

TEST_CASE("force translation: every shipped script gives the VM's results") {
  namespace fs = std::filesystem;
  int translated = 0;
  int scripts = 0;
  for (const auto& dir : {fs::path(HAPSCENE_SOURCE_DIR) / "scripts", fs::path(HAPSCENE_SOURCE_DIR) / "scripts" / "planar"}) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().extension() != ".lua") continue;
      const std::string name = fs::relative(entry.path(), HAPSCENE_SOURCE_DIR).string();
      CAPTURE(name);
      std::ifstream in(entry.path());
      std::ostringstream text;
      text << in.rdbuf();
      const bool planar = dir.filename() == "planar";
      const ScriptProgram program = planar ? compile_planar(name, text.str())
                                           : compile_script(name, text.str(), nlohmann::json::object(),
                                                            "environments/lab.json", "/effects/0/params");
      ++scripts;
      if (ScriptInstance::create(program)->force_translated()) {
        ++translated;
        MESSAGE(name << " runs translated");
      }
      if (planar) {
        check_same_2d(program);
      } else {
        check_same_1d(program);
      }
    }
  }
  MESSAGE(translated << " of " << scripts << " shipped scripts run translated");
  CHECK(translated >= 4);
}

TEST_CASE("force translation: a 2-D spring runs without the VM, to the bit") {
  const ScriptProgram program = compile_planar(
      "spring2.lua", "local K, cx, cy = 100, -0.015, 0.1275\nneeds = {velocity = false, time = false}\n"
                     "function force(s) return -K * (s.x - cx), -K * (s.y - cy) end");
  CHECK(ScriptInstance::create(program)->force_translated());
  check_same_2d(program);
}

TEST_CASE("force translation: what stays in the VM") {
  const auto translated = [](const char* source) { return test::run_inline(source)->force_translated(); };
  CHECK(translated("function force(s) return -100 * s.x end"));
  CHECK(translated("local K = 2.5\nfunction force(s) if s.x > 0.01 then return -K * s.v end return 0 end"));
  CHECK_FALSE(translated("function force(s) return math.abs(s.x) end"));              // a call
  CHECK_FALSE(translated("function force(s) return -math.pi * s.x end"));             // a global
  CHECK_FALSE(translated("local n = 0\nfunction force(s) n = n + 1 return 0 end"));  // writes an upvalue
  CHECK_FALSE(translated("local m = {k = 1}\nfunction force(s) return m.k * s.x end"));  // a table
  CHECK_FALSE(translated("local n = 3\nfunction force(s) return n // 2 end"));       // integer arithmetic
  CHECK_FALSE(translated("local q = 's'\nfunction force(s) return #q * s.x end"));    // a string
  CHECK_FALSE(translated("function force(s) local a = s return a.x end"));           // s escapes
  CHECK_FALSE(translated("function force(s) local a = 0 for i = 1, 2 do a = a + s.x end return a end"));
  // A function longer than the budget: the VM counts it, and faults; no translation.
  std::string longer = "function force(s)\n  local a = s.x\n  if s.x > 0.01 then\n";
  for (int i = 0; i < 60; ++i) longer += "    a = a * 1.0001 + 0.5\n";
  longer += "  end\n  return a\nend\n";
  ScriptLimits tight;
  tight.instructions_per_call = 100;
  const ScriptProgram program = test::compile_inline(longer, tight);
  CHECK_FALSE(ScriptInstance::create(program)->force_translated());
  check_same_1d(program);
  auto script = ScriptInstance::create(program);
  script->force_N(at(0.02));
  CHECK(script->disabled());
  CHECK(std::string(script->fault_message()).find("instruction budget exceeded") != std::string::npos);
}

TEST_CASE("force translation: a bad result is the VM's fault, word for word") {
  for (const char* source : {
           "function force(s) return 1 / s.x end",                        // inf at x = 0 ... after load
           "function force(s) if s.x > 0.02 then return 0 / 0 end return 0 end",
           "function force(s) if s.x > 0.02 then return end return 0 end",  // nothing returned
       }) {
    CAPTURE(source);
    try {
      check_same_1d(test::compile_inline(source));
    } catch (const InputError&) {
      // a fault at x = 0 is a load error for both; nothing to compare at run time
    }
  }
  auto script = test::run_inline("function force(s) if s.x > 0.02 then return 0 / 0 end return -s.x end");
  CHECK(script->force_translated());
  CHECK(script->force_N(at(0.01)) == -0.01);
  CHECK(script->force_N(at(0.03)) == 0.0);
  CHECK(script->disabled());
  CHECK(std::string(script->fault_message()).find("force(s) returned") != std::string::npos);
}

TEST_CASE("force translation: reset() changing an upvalue is followed, a non-number stops it") {
  const char* source =
      "local K, n = 2.0, 0\n"
      "function reset() n = n + 1 if n == 4 then K = {} else K = K * 1.5 end end\n"
      "function force(s) return -K * s.x end";
  const ScriptProgram program = test::compile_inline(source);
  ScriptProgram vm_program = program;
  vm_program.limits.translate_force = false;
  auto translated = ScriptInstance::create(program);
  auto vm = ScriptInstance::create(vm_program);
  for (int round = 0; round < 4; ++round) {
    translated->reset();
    vm->reset();
    CHECK(translated->force_translated() == (round < 3));
    for (double x : {0.01, -0.02, 0.003}) {
      REQUIRE(bits(translated->force_N(at(x))) == bits(vm->force_N(at(x))));
    }
    CHECK(translated->disabled() == vm->disabled());
    CHECK(std::string(translated->fault_message()) == std::string(vm->fault_message()));
  }
  CHECK(translated->disabled());  // {} * x: the VM's arithmetic error
}

TEST_CASE("force translation: a metamethod set in reset() hands force back to the VM") {
  auto script = test::run_inline(
      "local m = {}\nlocal K = 3.0\n"
      "function reset() setmetatable(m, {__index = function() return 1 end}) end\n"
      "function force(s) return -K * s.x end");
  CHECK(script->force_translated());
  script->reset();
  CHECK_FALSE(script->force_translated());
  CHECK(script->force_N(at(0.01)) == -0.03);
}

// Integers the translation cannot hold as doubles: 2^53 + 1 rounds to 2^53, 2^63 - 1 to
// 2^63, and Lua compares integers with floats exactly, so each comparison below goes the
// other way in a translation that rounds them (the force changes sign). Each is written
// with the integer as a constant and as an upvalue, and run in 1-D and 2-D.
TEST_CASE("force translation: integers beyond a double's precision compare as the VM compares them") {
  struct Edge {
    const char* integer;     // an integer literal
    const char* comparison;  // with I standing for it
  };
  const Edge edges[] = {
      {"9007199254740993", "I > 9007199254740992.0"},      // 2^53 + 1 > 2^53: true
      {"9007199254740993", "I == 9007199254740992.0"},     // false
      {"9007199254740993", "9007199254740992.0 >= I"},     // false
      {"-9007199254740993", "I < -9007199254740992.0"},    // true
      {"9223372036854775807", "I < 9223372036854775808.0"},  // 2^63 - 1 < 2^63: true
      {"9223372036854775807", "I ~= 2^63"},                // true
      {"9223372036854775807", "I >= 2^63"},                // false
      {"(-9223372036854775807 - 1)", "I <= -2^63"},       // the minimum integer: -2^63 <= -2^63
      {"(-9223372036854775807 - 1)", "-I < 0"},           // -minimum wraps to itself: true
      {"(-9223372036854775807 - 1)", "-I > 2^62"},        // false
      {"math.mininteger", "-I < 0"},
      {"math.maxinteger", "I + 0.0 == 2^63"},            // arithmetic converts: true
      {"9007199254740993", "I * 1.0 == 9007199254740992.0"},  // true
      {"9007199254740993", "s.x + I > 9007199254740992.0"},   // false at x = 0, true further
  };
  for (const Edge& edge : edges) {
    std::string comparison = edge.comparison;
    const auto with = [&](const std::string& name) {
      std::string out = comparison;
      for (std::size_t at = out.find('I'); at != std::string::npos; at = out.find('I', at + name.size())) {
        out.replace(at, 1, name);
      }
      return out;
    };
    const std::string constant_cmp = with(std::string("(") + edge.integer + ")");
    const std::string upvalue_cmp = with("E");
    for (const std::string& source : {
             "function force(s) if " + constant_cmp + " then return -s.x - 0.25 end return s.x + 0.25 end",
             std::string("local E = ") + edge.integer + "\nfunction force(s) if " + upvalue_cmp +
                 " then return -s.x - 0.25 end return s.x + 0.25 end",
         }) {
      CAPTURE(source);
      check_same_1d(test::compile_inline(source));
    }
    const std::string planar = std::string("local E = ") + edge.integer + "\nfunction force(s) if " + upvalue_cmp +
                               " then return -s.x - 0.25, 0.5 end return s.x + 0.25, -s.y end";
    CAPTURE(planar);
    check_same_2d(compile_planar("edge.lua", planar));
  }
  // Integers that are exactly doubles still run translated, and agree.
  for (const char* source : {
           "local E = 9007199254740992\nfunction force(s) if E > 9007199254740991.0 then return -s.x end return s.x end",
           "local E = -9007199254740991\nfunction force(s) return s.x * -E end",
           "local E = 1152921504606846976\nfunction force(s) if E == 2^60 then return -s.x end return s.x end",
       }) {
    CAPTURE(source);
    CHECK(test::run_inline(source)->force_translated());
    check_same_1d(test::compile_inline(source));
  }
}

TEST_CASE("force translation: an integer upvalue that reset() pushes past 2^53 hands force back to the VM") {
  // 2^53 - 1, then 2^53 (exact, still translated), then 2^53 + 1 (compares above 2^53.0).
  const char* source =
      "local K = 9007199254740990\n"
      "function reset() K = K + 1 end\n"
      "function force(s) if K > 9007199254740992.0 then return -s.x - 1 end return s.x + 1 end";
  const ScriptProgram program = test::compile_inline(source);
  ScriptProgram vm_program = program;
  vm_program.limits.translate_force = false;
  auto translated = ScriptInstance::create(program);
  auto vm = ScriptInstance::create(vm_program);
  for (int round = 0; round < 3; ++round) {
    translated->reset();
    vm->reset();
    CAPTURE(round);
    CHECK(translated->force_translated() == (round < 2));
    for (double x : {0.01, -0.02}) REQUIRE(bits(translated->force_N(at(x))) == bits(vm->force_N(at(x))));
  }
  CHECK(vm->force_N(at(0.01)) == -1.01);  // 2^53 + 1 > 2^53.0
}

// Random formulas over s's fields, numeric upvalues (integers and floats) and constants,
// with every arithmetic operator, comparisons and early returns: the translation must
// agree with the VM on every one it takes, and take most of them.
struct FormulaMaker {
  std::mt19937 random{20261124};
  // Integer edges as leaves too: 2^53 - 1, 2^53 + 1, 2^63 - 1 and the minimum integer as
  // constants (e, f, g, h as upvalues), with floats next to them (2^53, 2^63).
  bool edges = false;
  // 2-D: s.y, s.vx, s.vy instead of s.v.
  bool planar = false;

  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random); }

  std::string edge() {
    static const char* kEdges[] = {"9007199254740991", "9007199254740993", "9223372036854775807",
                                   "(-9223372036854775807 - 1)", "-9007199254740993", "9007199254740992.0",
                                   "2^63", "e", "f", "g", "h", "k"};
    return kEdges[pick(12)];
  }

  std::string leaf() {
    static const char* kLeaves[] = {"s.x", "s.v", "s.t", "s.dt", "a", "b", "c", "d", "2", "-3", "0.5",
                                    "-0.0", "1e-3", "7", "0.25", "3.5"};
    static const char* kPlanar[] = {"s.y", "s.vx", "s.vy"};
    if (edges && pick(2) == 0) return edge();
    const char* out = kLeaves[pick(16)];
    if (planar && std::string(out) == "s.v") return kPlanar[pick(3)];
    return out;
  }
  std::string expression(int depth) {
    if (depth == 0 || pick(4) == 0) return leaf();
    static const char* kOps[] = {" + ", " - ", " * ", " / ", " % ", " // ", " ^ ", " ^ 2"};
    const int op = pick(9);
    if (op == 8) return "-(" + expression(depth - 1) + ")";
    if (op == 7) return "(" + expression(depth - 1) + ")" + kOps[7];
    return "(" + expression(depth - 1) + kOps[op] + expression(depth - 1) + ")";
  }
  std::string comparison() {
    static const char* kCmp[] = {" < ", " <= ", " > ", " >= ", " == ", " ~= "};
    // With edges, half the comparisons are of two edges (2^53 + 1 against 2^53.0 ...).
    if (edges && pick(2) == 0) return edge() + kCmp[pick(6)] + edge();
    return expression(1) + kCmp[pick(6)] + expression(1);
  }
  // In 2-D every return gives two values (the second a short formula).
  std::string second() { return planar ? ", " + expression(1) : ""; }
  std::string source() {
    std::string body;
    switch (pick(5)) {
      case 0: body = "  return " + expression(3) + second() + "\n"; break;
      case 1:
        body = "  if " + comparison() + " then return " + expression(2) + second() + " end\n  return " +
               expression(2) + second() + "\n";
        break;
      case 2:
        body = "  local u = " + expression(2) + "\n  if u > " + leaf() + " then return u * " + leaf() + second() +
               " elseif " + comparison() + " then return -u" + second() + " end\n  return " + expression(1) +
               second() + "\n";
        break;
      case 3:
        body = "  local g\n  if " + comparison() + " then g = " + expression(2) + " else g = " + expression(1) +
               " end\n  return g * " + leaf() + second() + "\n";
        break;
      default: body = "  local p, q = " + expression(2) + ", " + expression(2) + "\n  return p - q, q\n"; break;
    }
    std::string upvalues = "local a, b, c, d = 1.5, 2, -0.75, 10\n";
    if (edges) {
      upvalues += "local e, f, g, h, k = 9007199254740991, 9007199254740993, math.maxinteger, math.mininteger, "
                  "9007199254740992.0\n";
    }
    return upvalues + "function force(s)\n" + body + "end\n";
  }
};

TEST_CASE("force translation: random formulas agree with the VM to the bit") {
  FormulaMaker maker;
  int compared = 0;
  int translated = 0;
  for (int i = 0; i < 2000; ++i) {
    const std::string source = maker.source();
    CAPTURE(source);
    ScriptProgram program;
    try {
      program = test::compile_inline(source);
    } catch (const InputError&) {
      continue;  // faulted at x = 0 while loading: nothing runs
    }
    ++compared;
    if (ScriptInstance::create(program)->force_translated()) ++translated;
    check_same_1d(program);
  }
  MESSAGE(translated << " of " << compared << " formulas ran translated");
  CHECK(compared >= 1000);
  CHECK(translated * 2 >= compared);
}

// The same with integers at the edges of a double's precision and of the integer range,
// mixed with floats in comparisons and arithmetic, as constants and as upvalues, in 1-D
// and in 2-D (where force returns two values: a one-value return is the VM's fault).
TEST_CASE("force translation: random formulas with integer edges agree with the VM to the bit") {
  for (const bool planar : {false, true}) {
    FormulaMaker maker;
    maker.edges = true;
    maker.planar = planar;
    int compared = 0;
    int translated = 0;
    for (int i = 0; i < 1500; ++i) {
      const std::string source = maker.source();
      CAPTURE(source);
      ScriptProgram program;
      try {
        program = planar ? compile_planar("edges.lua", source) : test::compile_inline(source);
      } catch (const InputError&) {
        continue;  // faulted while loading: nothing runs
      }
      ++compared;
      if (ScriptInstance::create(program)->force_translated()) ++translated;
      if (planar) {
        check_same_2d(program);
      } else {
        check_same_1d(program);
      }
    }
    MESSAGE((planar ? "2-D: " : "1-D: ") << translated << " of " << compared << " formulas ran translated");
    CHECK(compared >= 200);
    CHECK(translated * 8 >= compared);  // most leave an integer edge to the VM
  }
}

}  // namespace
}  // namespace hapscene
