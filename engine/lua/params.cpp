#include "engine/lua/params.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"

namespace hapscene {
namespace {

// "<declared_at>: params.<name>: <message>": a problem in the script's own defaults.
[[noreturn]] void default_error(const DeclaredParam& d, const ParamPlaces& places,
                                const std::string& message) {
  const std::string_view at = d.declared_at.empty() ? places.declared_at : d.declared_at;
  throw InputError(std::string(at) + ": params." + d.name + ": " + message);
}

// "<context>: <prefix>/<key>: <message>": a problem in the JSON overrides.
[[noreturn]] void override_error(const ParamPlaces& places, std::string_view key,
                                 const std::string& message) {
  std::string text;
  if (!places.error_context.empty()) text += std::string(places.error_context) + ": ";
  text += std::string(places.pointer_prefix) + "/" + json_pointer_token(key) + ": " + message;
  throw InputError(text);
}

// A JSON value as written in a message: strings quoted, the rest as JSON.
std::string describe(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A string default that begins like a number is meant as a quantity.
bool looks_like_quantity(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return false;
  const char c = text[first];
  return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.';
}

// Converts one declared default to a parameter (SI), or throws naming it.
ScriptParam from_default(const DeclaredParam& d, const ParamPlaces& places) {
  if (d.name.empty()) {
    const std::string_view at = d.declared_at.empty() ? places.declared_at : d.declared_at;
    throw InputError(std::string(at) + ": params[" + d.key_text +
                     "]: parameter names must be strings");
  }
  ScriptParam p;
  p.name = d.name;
  switch (d.type) {
    case DeclaredParam::Type::number:
      if (!std::isfinite(d.number)) {
        default_error(d, places, "must be a finite number, got " + std::to_string(d.number));
      }
      p.kind = ScriptParam::Kind::number;
      p.value_si = d.number;
      return p;
    case DeclaredParam::Type::boolean:
      p.kind = ScriptParam::Kind::boolean;
      p.flag = d.boolean;
      return p;
    case DeclaredParam::Type::string:
      if (looks_like_quantity(d.text)) {
        const QuantityParse q = parse_quantity(d.text);
        if (!q.ok) default_error(d, places, q.error);
        p.kind = ScriptParam::Kind::number;
        p.value_si = q.value_si;
        p.has_unit = q.quantity != Quantity::dimensionless;
        p.quantity = q.quantity;
        return p;
      }
      p.kind = ScriptParam::Kind::text;
      p.text = d.text;
      return p;
    case DeclaredParam::Type::other:
      break;
  }
  default_error(d, places,
                "a parameter default must be a number, a boolean or a string, got a " + d.text);
}

// Replaces a parameter's value by its JSON override, or throws naming the override.
void apply_override(const std::string& key, const nlohmann::json& value, const ParamPlaces& places,
                    ScriptParam* p) {
  p->overridden = true;
  switch (p->kind) {
    case ScriptParam::Kind::number: {
      if (value.is_number()) {
        p->value_si = value.get<double>();
        return;
      }
      if (value.is_string()) {
        const std::string text = value.get<std::string>();
        if (p->has_unit) {
          const QuantityParse q = parse_quantity_as(text, p->quantity);
          if (!q.ok) override_error(places, key, q.error);
          p->value_si = q.value_si;
          return;
        }
        const QuantityParse q = parse_quantity(text);
        if (!q.ok) override_error(places, key, q.error);
        if (q.quantity != Quantity::dimensionless) {
          override_error(places, key,
                         "expected a plain number (the script's default has no unit), got a " +
                             std::string(quantity_name(q.quantity)) + " (" + describe(value) + ")");
        }
        p->value_si = q.value_si;
        return;
      }
      if (p->has_unit) {
        override_error(places, key,
                       "expected a " + std::string(quantity_name(p->quantity)) + " (" +
                           std::string(si_unit(p->quantity)) +
                           "): a number or a string such as \"1 " +
                           std::string(si_unit(p->quantity)) + "\", got " + describe(value));
      }
      override_error(places, key, "expected a number, got " + describe(value));
    }
    case ScriptParam::Kind::boolean:
      if (!value.is_boolean()) {
        override_error(places, key, "expected true or false, got " + describe(value));
      }
      p->flag = value.get<bool>();
      return;
    case ScriptParam::Kind::text:
      if (!value.is_string()) override_error(places, key, "expected a string, got " + describe(value));
      p->text = value.get<std::string>();
      return;
  }
}

// The message for an override the script does not declare: the nearest name, or the list.
std::string undeclared_message(const std::string& key, const std::vector<ScriptParam>& params,
                               std::string_view script_name) {
  std::string message =
      std::string(script_name) + " has no parameter \"" + key + "\"";
  if (params.empty()) return message + " (it declares no params)";
  std::vector<std::string> names;
  for (const ScriptParam& p : params) names.push_back(p.name);
  const std::string suggestion = nearest_name(key, names);
  if (!suggestion.empty()) return message + " (did you mean \"" + suggestion + "\"?)";
  message += " (its params are:";
  for (const std::string& name : names) message += " " + name;
  return message + ")";
}

}  // namespace

std::vector<ScriptParam> resolve_params(std::vector<DeclaredParam> declared,
                                        const nlohmann::json& overrides,
                                        const ParamPlaces& places) {
  // Defaults, in name order so that the first error reported does not depend on Lua's
  // table order.
  std::sort(declared.begin(), declared.end(),
            [](const DeclaredParam& a, const DeclaredParam& b) { return a.name < b.name; });
  std::vector<ScriptParam> params;
  params.reserve(declared.size());
  for (const DeclaredParam& d : declared) params.push_back(from_default(d, places));

  // Overrides, in the JSON object's (sorted) order.
  if (overrides.is_null()) return params;
  if (!overrides.is_object()) {
    std::string text;
    if (!places.error_context.empty()) text += std::string(places.error_context) + ": ";
    text += std::string(places.pointer_prefix.empty() ? "/" : places.pointer_prefix) +
            ": params must be an object, got " + describe(overrides);
    throw InputError(text);
  }
  for (const auto& [key, value] : overrides.items()) {
    // params is sorted by name: a binary search, so many overrides stay cheap.
    auto it = std::lower_bound(params.begin(), params.end(), key,
                               [](const ScriptParam& p, const std::string& k) { return p.name < k; });
    if (it == params.end() || it->name != key) {
      override_error(places, key, undeclared_message(key, params, places.script_name));
    }
    apply_override(key, value, places, &*it);
  }
  return params;
}

std::string json_pointer_token(std::string_view key) {
  std::string token;
  for (const char c : key) {
    if (c == '~') {
      token += "~0";
    } else if (c == '/') {
      token += "~1";
    } else {
      token += c;
    }
  }
  return token;
}

}  // namespace hapscene
