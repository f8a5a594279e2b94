#include "engine/load/effect_schema.hpp"

#include <cmath>
#include <string>

#include "engine/base/object_reader.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/effects/vector_reader.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {
namespace {

using Schema = nlohmann::ordered_json;  // key order as written

// The schemas' name of a quantity (its "#/$defs/KIND_text" string form).
std::string kind_of(Quantity quantity) {
  if (quantity == Quantity::dimensionless) return "plain";
  if (quantity == Quantity::inertia_kg_m2) return "inertia";
  std::string kind(quantity_name(quantity));
  for (char& c : kind) {
    if (c == ' ') c = '_';
  }
  return kind;
}

// A bound as JSON: a whole number when it is one (as people write them), else a double.
Schema bound(double value) {
  if (std::fabs(value) < 1e15 && value == std::floor(value)) return static_cast<long long>(value);
  return value;
}

// A number (SI) within the key's range, or a string with a unit of its quantity.
Schema quantity(Quantity quantity_kind, const Range& range, const std::string& description) {
  Schema number = {{"type", "number"}};
  number[range.min_excluded ? "exclusiveMinimum" : "minimum"] = bound(range.min);
  number["maximum"] = bound(range.max);
  const std::string kind = kind_of(quantity_kind);
  const std::string unit(si_unit(quantity_kind));
  std::string what = kind;
  for (char& c : what) {
    if (c == '_') c = ' ';
  }
  const std::string form = unit.empty() ? "a plain number (or a string holding one)"
                                        : "a " + what + ": a number in " + unit + " or a string with a unit";
  return {{"anyOf", {number, {{"$ref", "#/$defs/" + kind + "_text"}}}},
          {"description", description.empty() ? form : description + " (" + form + ")"}};
}

// An array of exactly `count` items.
Schema vector_of(const Schema& item, int count, const std::string& description) {
  Schema items = Schema::array();
  for (int i = 0; i < count; ++i) items.push_back(item);
  return {{"type", "array"}, {"prefixItems", items}, {"minItems", count}, {"maxItems", count}, {"items", false},
          {"description", description}};
}

Schema with_description(Schema schema, std::string_view description) {
  if (!description.empty()) schema["description"] = std::string(description);
  return schema;
}

// One key's schema in an effect of `axes` axes.
Schema key_schema(const EffectKey& key, int axes) {
  const std::string description(key.description);
  const std::string unit(si_unit(key.quantity));
  const std::string component_form =
      bracket_form(axes) + (unit.empty() ? std::string(" numbers") : " in " + unit + " (or strings with a unit)");
  switch (key.form) {
    case KeyForm::number:
      return quantity(key.quantity, key.range, description);
    case KeyForm::vector:
      if (axes == 1) return quantity(key.quantity, key.range, description);
      return vector_of(quantity(key.quantity, key.range, ""), axes,
                       description.empty() ? component_form : description + ": " + component_form);
    case KeyForm::direction:
      return vector_of(quantity(key.quantity, key.range, ""), axes, description + " (not the zero vector)");
    case KeyForm::choice:
      return with_description({{"enum", {std::string(key.choices[0]), std::string(key.choices[1])}}}, description);
    case KeyForm::flag:
      return with_description({{"type", "boolean"}}, description);
    case KeyForm::points:
      return {{"type", "array"},
              {"items", vector_of(quantity(key.quantity, key.range, ""), axes, component_form)},
              {"minItems", key.min_items},
              {"maxItems", key.max_items},
              {"description", description}};
    case KeyForm::friction: {
      const Schema coefficient = quantity(key.quantity, key.range, "");
      return {{"type", "object"},
              {"properties", {{"static", coefficient}, {"dynamic", coefficient}}},
              {"additionalProperties", false},
              {"required", {"static", "dynamic"}},
              {"description", description}};
    }
    case KeyForm::refused:
      break;
  }
  return Schema();
}

// One effect type: a closed object of its "type", "enabled" and declared keys.
Schema effect_schema(const EffectDeclaration& declaration) {
  Schema properties = {{"type", {{"const", std::string(declaration.type)}}}, {"enabled", {{"type", "boolean"}}}};
  Schema required = {"type"};
  for (const EffectKey& key : declaration.keys) {
    if (key.form == KeyForm::refused) continue;  // not a key of this form: additionalProperties refuses it
    properties[std::string(key.name)] = key_schema(key, declaration.axes);
    if (key.required) required.push_back(std::string(key.name));
  }
  return {{"type", "object"},
          {"properties", properties},
          {"additionalProperties", false},
          {"required", required},
          {"description", std::string(declaration.description)}};
}

// A range as people read it: "-1000 to 1000 m", "above 0, up to 1000 m".
std::string range_text(const EffectKey& key) {
  const std::string unit(si_unit(key.quantity));
  const std::string tail = unit.empty() ? "" : " " + unit;
  if (key.range.min_excluded) return "above " + format_number(key.range.min) + ", up to " + format_number(key.range.max) + tail;
  return format_number(key.range.min) + " to " + format_number(key.range.max) + tail;
}

// What a key takes, for the page's "value" column.
std::string form_text(const EffectKey& key, int axes) {
  const std::string unit(si_unit(key.quantity));
  const std::string per_axis = axes == 1 ? "" : bracket_form(axes) + " of ";
  switch (key.form) {
    case KeyForm::number: return "a " + std::string(quantity_name(key.quantity)) + ", " + range_text(key);
    case KeyForm::vector:
      return (axes == 1 ? "a " : per_axis + "") + std::string(quantity_name(key.quantity)) + (axes == 1 ? ", " : "s, each ") +
             range_text(key);
    case KeyForm::direction: return "a direction " + bracket_form(axes) + " (any length but zero)";
    case KeyForm::choice:
      return "`\"" + std::string(key.choices[0]) + "\"` or `\"" + std::string(key.choices[1]) + "\"`";
    case KeyForm::flag: return "`true` or `false`";
    case KeyForm::points:
      return std::to_string(key.min_items) + " to " + std::to_string(key.max_items) + " points " + bracket_form(axes) +
             " in " + unit;
    case KeyForm::friction: return "`{\"static\": mu_s, \"dynamic\": mu_d}`, each " + range_text(key);
    case KeyForm::refused: break;
  }
  return "";
}

std::string default_text(const EffectKey& key) {
  if (key.required) return "required";
  if (!key.fallback_from.empty()) return "`" + std::string(key.fallback_from) + "`";
  if (key.form == KeyForm::flag) return key.fallback_si != 0.0 ? "`true`" : "`false`";
  if (key.form == KeyForm::number || key.form == KeyForm::vector) {
    const std::string unit(si_unit(key.quantity));
    return format_number(key.fallback_si) + (unit.empty() ? "" : " " + unit);
  }
  return "none";
}

}  // namespace

std::string effect_reference_markdown() {
  std::string out;
  out += "# Built-in effects: every key\n\n";
  out += "<!-- Generated by `hapscene schema effects --markdown`; do not edit: change the effect's declaration "
         "(engine/effects/effect_keys.hpp) and run tests/docs/effect_keys.sh BINARY --write. -->\n\n";
  out += "Every built-in effect of every number of axes, as the engine declares it: the loader, the live view's "
         "sliders, the Python module (`hapscene.effect_types()`, `Scene.effects`) and the JSON Schema "
         "(`hapscene schema effects`) read the same declaration. A number is SI, or a string with a unit "
         "(`\"10 mm\"`); every effect also takes `\"enabled\"`. What each force law means is in "
         "[Environment files](environments.md).\n";
  const auto add = [&](const EffectDeclaration& declaration) {
    out += "\n## `" + std::string(declaration.type) + "` (" + std::to_string(declaration.axes) + "-D)\n\n";
    out += std::string(declaration.description) + ".\n\n";
    out += "| key | value | default | slider | compiled as | what |\n| --- | --- | --- | --- | --- | --- |\n";
    for (const EffectKey& key : declaration.keys) {
      if (key.form == KeyForm::refused) continue;
      out += "| `" + std::string(key.name) + "` | " + form_text(key, declaration.axes) + " | " + default_text(key) + " | " +
             (key.slidable ? "yes" : "no") + " | " + (key.field.empty() ? "" : "`" + std::string(key.field) + "`") +
             " | " + std::string(key.description) + " |\n";
    }
  };
#define HAPSCENE_EFFECT_PAGE(N) \
  for (const EffectDeclaration& declaration : SceneParts<N>::Effects::kDeclarations) add(declaration);
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_EFFECT_PAGE)
#undef HAPSCENE_EFFECT_PAGE
  return out;
}

nlohmann::ordered_json effect_schemas() {
  Schema out = Schema::object();
#define HAPSCENE_EFFECT_SCHEMAS(N)                                                           \
  for (const EffectDeclaration& declaration : SceneParts<N>::Effects::kDeclarations) {      \
    out["effect_" + std::to_string(N) + "d_" + std::string(declaration.type)] = effect_schema(declaration); \
  }
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_EFFECT_SCHEMAS)
#undef HAPSCENE_EFFECT_SCHEMAS
  return out;
}

}  // namespace hapscene
