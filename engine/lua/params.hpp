#pragma once
// Script parameters: the defaults a script declares in its `params` table, and the
// overrides from the JSON `params` object, resolved to SI values. Pure C++ (no Lua), so
// the rules are tested directly:
// - A default is a number, a boolean or a string. A string that begins with a number is a
//   quantity: "2 mm" declares a length, "3" a plain number; any other string is text.
// - An override must name a declared parameter and match its kind. A unit default
//   accepts a number (SI) or a string of the same quantity ("3 mm", "0.003"); a plain
//   number default accepts a number or a unit-less string ("3"), never a unit, so a
//   script author decides which parameters carry units.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/lua/script.hpp"

namespace hapscene {

// One entry of the script's `params` table, as read from Lua.
struct DeclaredParam {
  enum class Type { number, boolean, string, other };
  std::string name;        // empty when the key is not a string
  std::string key_text;    // how to show the key in a message when it is not a string
  Type type{Type::other};
  double number{};
  bool boolean{};
  std::string text;        // string value, or the Lua type name for Type::other
  std::string declared_at; // "scripts/bumps.lua:4" when known, else ParamPlaces::declared_at
};

// Where the messages point.
struct ParamPlaces {
  std::string_view script_name;     // "scripts/bumps.lua"
  std::string_view declared_at;     // "scripts/bumps.lua:3", where `params` is assigned
  std::string_view error_context;   // "environments/lab.json" (may be empty)
  std::string_view pointer_prefix;  // "/effects/2/params" (may be empty)
};

// Resolves defaults and overrides; the result is sorted by name. Throws InputError:
//   "scripts/bumps.lua:3: params.height: unknown unit \"mmm\" (did you mean \"mm\"?)"
//   "environments/lab.json: /effects/2/params/hieght: scripts/bumps.lua has no parameter
//    \"hieght\" (did you mean \"height\"?)"
std::vector<ScriptParam> resolve_params(std::vector<DeclaredParam> declared,
                                        const nlohmann::json& overrides, const ParamPlaces& places);

// "a/b" -> "a~1b": a key as one JSON pointer token (RFC 6901).
std::string json_pointer_token(std::string_view key);

}  // namespace hapscene
