#pragma once
// Helpers for the script tests: compile inline sources or the shipped scripts/ files,
// and catch the load error text.
#include <doctest/doctest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/lua/script.hpp"

namespace hapscene::test {

// The text of scripts/<name> in the source tree.
inline std::string read_script(std::string_view name) {
  const std::string path = std::string(HAPSCENE_SOURCE_DIR) + "/scripts/" + std::string(name);
  std::ifstream in(path, std::ios::binary);
  REQUIRE_MESSAGE(in.good(), "cannot open " << path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A shipped script compiled as a JSON environment would: display name "scripts/<name>",
// overrides from "environments/lab.json" at /effects/2/params.
inline ScriptProgram compile_shipped(std::string_view name,
                                     const nlohmann::json& overrides = nlohmann::json::object()) {
  return compile_script("scripts/" + std::string(name), read_script(name), overrides,
                        "environments/lab.json", "/effects/2/params");
}

// An inline source named "t.lua".
inline ScriptProgram compile_inline(std::string source, ScriptLimits limits = {},
                                    const nlohmann::json& overrides = nlohmann::json::object()) {
  return compile_script("t.lua", std::move(source), overrides, "environments/lab.json",
                        "/effects/2/params", limits);
}

// A fresh run instance of an inline source.
inline std::unique_ptr<ScriptInstance> run_inline(std::string source, ScriptLimits limits = {}) {
  return ScriptInstance::create(compile_inline(std::move(source), limits));
}

// The InputError message compiling an inline source gives, or "" when it compiles.
inline std::string script_load_error(std::string source, const nlohmann::json& overrides =
                                                      nlohmann::json::object(),
                              ScriptLimits limits = {}, std::string display_name = "t.lua") {
  try {
    compile_script(std::move(display_name), std::move(source), overrides, "environments/lab.json",
                   "/effects/2/params", limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The state handed to force(s).
inline ScriptInput at(double x_m, double v_m_per_s = 0.0, double t_s = 0.0, double dt_s = 0.001) {
  ScriptInput input;
  input.x_m = x_m;
  input.v_m_per_s = v_m_per_s;
  input.t_s = t_s;
  input.dt_s = dt_s;
  return input;
}

// The suffix compile_script adds to faults found by its check call of force(s).
inline constexpr std::string_view kProbeSuffix =
    " (while checking force(s) at x = 0 m, v = 0 m/s, t = 0 s)";

}  // namespace hapscene::test
