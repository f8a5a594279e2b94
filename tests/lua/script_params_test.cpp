// Params: defaults declared in the script (unit strings become SI numbers), JSON
// overrides that must name a declared parameter of the same kind, and messages that
// point at the script line or the JSON pointer.
#include "engine/lua/params.hpp"
#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;
using test::compile_inline;
using test::script_load_error;
using test::run_inline;

constexpr const char* kDeclared = R"(
params = {
  stiffness = "100 N/m",
  height = "2 mm",
  count = 3,
  enabled = true,
  mode = "left",
}
function force(s) return 0 end
)";

const ScriptParam& param(const ScriptProgram& program, const std::string& name) {
  for (const ScriptParam& p : program.params) {
    if (p.name == name) return p;
  }
  FAIL("no param " << name);
  throw;
}

TEST_CASE("params: defaults become SI values, sorted by name") {
  const ScriptProgram program = compile_inline(kDeclared);
  REQUIRE(program.params.size() == 5);
  CHECK(program.params[0].name == "count");
  CHECK(program.params[4].name == "stiffness");
  CHECK(param(program, "stiffness").value_si == 100.0);
  CHECK(param(program, "stiffness").has_unit);
  CHECK(param(program, "stiffness").quantity == Quantity::stiffness_N_per_m);
  CHECK(param(program, "height").value_si == 2 * 1e-3);
  CHECK(param(program, "height").quantity == Quantity::length_m);
  CHECK(param(program, "count").value_si == 3.0);
  CHECK_FALSE(param(program, "count").has_unit);
  CHECK(param(program, "enabled").kind == ScriptParam::Kind::boolean);
  CHECK(param(program, "enabled").flag);
  CHECK(param(program, "mode").kind == ScriptParam::Kind::text);
  CHECK(param(program, "mode").text == "left");
  CHECK_FALSE(param(program, "mode").overridden);
}

TEST_CASE("params: the script sees SI values, already at the top level") {
  auto script = run_inline(R"(
    params = { height = "2 mm", stiffness = "1 N/mm" }
    local h = params.height          -- read once at load time
    assert(type(h) == "number")
    function force(s) return h * 1000 + params.stiffness end
  )");
  CHECK(script->force_N(at(0.0)) == doctest::Approx(1002.0));
}

TEST_CASE("params: overrides replace defaults, converted to SI") {
  const nlohmann::json overrides = {
      {"stiffness", "0.25 N/mm"}, {"height", 0.004}, {"count", "7"}, {"enabled", false},
      {"mode", "right"}};
  const ScriptProgram program = compile_inline(kDeclared, {}, overrides);
  CHECK(param(program, "stiffness").value_si == 0.25 * 1e3);
  CHECK(param(program, "stiffness").overridden);
  CHECK(param(program, "height").value_si == 0.004);
  CHECK(param(program, "count").value_si == 7.0);
  CHECK_FALSE(param(program, "enabled").flag);
  CHECK(param(program, "mode").text == "right");

  // Top-level code sees the overrides, not the defaults.
  const ScriptProgram scaled = compile_inline(
      "params = { gain = \"2 N/m\" }\nlocal k = params.gain\nfunction force(s) return k end", {},
      {{"gain", "5 N/m"}});
  CHECK(ScriptInstance::create(scaled)->force_N(at(0.0)) == 5.0);
}

TEST_CASE("params: an override must name a declared parameter") {
  CHECK(script_load_error(kDeclared, {{"stifness", "1 N/m"}}) ==
        "environments/lab.json: /effects/2/params/stifness: t.lua has no parameter \"stifness\" "
        "(did you mean \"stiffness\"?)");
  CHECK(script_load_error(kDeclared, {{"gain", 1}}) ==
        "environments/lab.json: /effects/2/params/gain: t.lua has no parameter \"gain\" (its params "
        "are: count enabled height mode stiffness)");
  CHECK(script_load_error("function force(s) return 0 end", {{"gain", 1}}) ==
        "environments/lab.json: /effects/2/params/gain: t.lua has no parameter \"gain\" (it "
        "declares no params)");
  // Keys are written as JSON pointer tokens.
  CHECK(script_load_error(kDeclared, {{"a/b~c", 1}}) ==
        "environments/lab.json: /effects/2/params/a~1b~0c: t.lua has no parameter \"a/b~c\" (its "
        "params are: count enabled height mode stiffness)");
}

TEST_CASE("params: an override must match the kind and quantity of the default") {
  const std::string prefix = "environments/lab.json: /effects/2/params/";
  CHECK(script_load_error(kDeclared, {{"height", "2 N/m"}}) ==
        prefix + "height: expected a length (m), got a stiffness (\"2 N/m\")");
  CHECK(script_load_error(kDeclared, {{"height", true}}) ==
        prefix + "height: expected a length (m): a number or a string such as \"1 m\", got true");
  CHECK(script_load_error(kDeclared, {{"height", "2 mmm"}}) ==
        prefix + "height: unknown unit \"mmm\" (did you mean \"mm\"?)");
  CHECK(script_load_error(kDeclared, {{"count", "2 mm"}}) ==
        prefix + "count: expected a plain number (the script's default has no unit), got a length "
                 "(\"2 mm\")");
  CHECK(script_load_error(kDeclared, {{"count", true}}) == prefix + "count: expected a number, got true");
  CHECK(script_load_error(kDeclared, {{"enabled", "yes"}}) ==
        prefix + "enabled: expected true or false, got \"yes\"");
  CHECK(script_load_error(kDeclared, {{"mode", 3}}) == prefix + "mode: expected a string, got 3");
  CHECK(script_load_error(kDeclared, nlohmann::json::array({1, 2})) ==
        "environments/lab.json: /effects/2/params: params must be an object, got [1,2]");
}

TEST_CASE("params: bad defaults point at the script's params line") {
  CHECK(script_load_error("params = { h = \"3 furlongs\" }") ==
        "t.lua:1: params.h: unknown unit \"furlongs\"");
  CHECK(script_load_error("params = { curve = { 1, 2 } }") ==
        "t.lua:1: params.curve: a parameter default must be a number, a boolean or a string, got "
        "a table");
  CHECK(script_load_error("params = { 5 }") == "t.lua:1: params[1]: parameter names must be strings");
  CHECK(script_load_error("params = { k = 1/0 }") == "t.lua:1: params.k: must be a finite number, got inf");
  CHECK(script_load_error("params = 3") ==
        "t.lua:1: params must be a table of defaults such as { stiffness = \"100 N/m\" }, got a "
        "number");
  // A table over several lines: the line of the field.
  CHECK(script_load_error("\nparams = {\n  a = 1,\n  b = \"2 qq\",\n  c = 2,\n}\n") ==
        "t.lua:4: params.b: unknown unit \"qq\" (did you mean \"m\"?)");
}

TEST_CASE("params: every parameter is declared in one table") {
  CHECK(script_load_error("params = { a = 1 }\nparams.b = 2") ==
        "t.lua:2: params.b is not declared: declare every parameter in the params table");
  CHECK(script_load_error("params = { a = 1 }\nparams = { b = 2 }\nfunction force(s) return 0 end") ==
        "t.lua: params was replaced after it was declared: declare every parameter in one params "
        "table");
  // A typo when reading is caught too.
  auto script = run_inline(
      "params = { stiffness = 100 }\n"
      "function force(s)\n"
      "  if s.x > 0 then return -params.stifness * s.x end\n"
      "  return 0\n"
      "end");
  CHECK(script->force_N(at(0.01)) == 0.0);
  CHECK(script->fault_message() ==
        "t.lua:3: params has no field 'stifness' (did you mean 'stiffness'?)");
}

TEST_CASE("params: resolve_params can be used without Lua") {
  DeclaredParam width;
  width.name = "width";
  width.type = DeclaredParam::Type::string;
  width.text = "5 mm";
  const ParamPlaces places{"scripts/texture.lua", "scripts/texture.lua:3", "", "/params"};
  const auto params = resolve_params({width}, {{"width", "1 cm"}}, places);
  REQUIRE(params.size() == 1);
  CHECK(params[0].value_si == 1 * 1e-2);
  CHECK(json_pointer_token("a/b~") == "a~1b~0");
  CHECK_THROWS_WITH_AS(resolve_params({width}, {{"width", "1 s"}}, places),
                       "/params/width: expected a length (m), got a time (\"1 s\")", InputError);
}

}  // namespace
}  // namespace hapscene
