#include "engine/effects/planar/planar_effect_types.hpp"

#include <algorithm>
#include <array>

#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/type_hint.hpp"
#include "engine/effects/declared_parse.hpp"

namespace hapscene {
namespace {

template <typename T>
constexpr PlanarEffectType planar_effect_type() {
  return PlanarEffectType{T::kType, [](ObjectReader& reader, ScriptLoadBudget* budget) {
                            if constexpr (std::is_same_v<T, ScriptEffect>) {
                              return PlanarEffect{T::parse(reader, *budget, 2)};
                            } else {
                              return PlanarEffect{parse_declared<T>(reader)};
                            }
                          }};
}

template <std::size_t... I>
constexpr auto make_table(std::index_sequence<I...>) {
  return std::array<PlanarEffectType, sizeof...(I)>{planar_effect_type<std::variant_alternative_t<I, PlanarEffect>>()...};
}

constexpr auto kPlanarEffectTypes = make_table(std::make_index_sequence<std::variant_size_v<PlanarEffect>>{});

}  // namespace

std::span<const PlanarEffectType> planar_effect_types() { return kPlanarEffectTypes; }

bool parse_planar_effect(const nlohmann::json& value, const std::string& pointer, const std::string& file,
                         PlanarEffect* effect, const std::string& base_dir, ScriptLoadBudget* budget) {
  ObjectReader reader(value, pointer, file, base_dir);
  const std::string type_name = reader.string("type");
  const auto types = planar_effect_types();
  const auto type = std::find_if(types.begin(), types.end(), [&](const PlanarEffectType& t) { return t.name == type_name; });
  if (type == types.end()) {
    std::vector<std::string_view> names;
    for (const PlanarEffectType& t : types) names.push_back(t.name);
    reader.fail("type", "unknown 2-D effect type \"" + type_name + "\"" + effect_type_hint(type_name, names));
  }
  if (const nlohmann::json* flag = reader.get("enabled")) {
    if (!flag->is_boolean()) reader.fail("enabled", "expected a boolean, got " + json_type_name(*flag));
    if (!flag->get<bool>()) return false;
  }
  ScriptLoadBudget own_budget{kScriptLoadBudget_s, 0.0};
  *effect = type->parse(reader, budget != nullptr ? budget : &own_budget);
  reader.finish();
  return true;
}

}  // namespace hapscene
