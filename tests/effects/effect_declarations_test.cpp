// Every built-in effect of every N against its declaration (engine/effects/effect_keys.hpp):
// the loader reads exactly the declared keys, with their requiredness, defaults and ranges;
// the schema (`hapscene schema effects`, and the committed schemas/environment.schema.json)
// lists the same keys; the live view offers a slider for each slidable one. A new effect
// type added to a list is checked here without a line of this file changing. (Python's
// view of the same declarations: python/tests/test_effect_declarations.py.)
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/load/effect_schema.hpp"
#include "engine/load/environment.hpp"
#include "engine/serve/parameters.hpp"
#include "tests/support.hpp"

namespace effect_declarations_test {

using namespace hapscene;
using nlohmann::json;

template <typename T, typename F>
void call_if_builtin(F& f) {
  if constexpr (!std::is_same_v<T, ScriptEffect>) f(std::type_identity<T>{});
}
template <typename F, typename... Types>
void for_each_alternative(F& f, std::variant<Types...>*) {
  (call_if_builtin<Types>(f), ...);
}
// Calls f(std::type_identity<T>{}) for each built-in effect type T of scenes with N axes.
template <int N, typename F>
void for_each_builtin(F f) {
  for_each_alternative(f, static_cast<typename SceneParts<N>::Effects::Variant*>(nullptr));
}

// A written value for the key at `index` of a declaration: inside its range, and different
// for each key (so a box's max lies above its min).
json example_value(const EffectKey& key, int axes, int index) {
  const double v = 0.01 * (index + 1);
  const auto per_axis = [&](double value) {
    if (axes == 1) return json(value);
    json array = json::array();
    for (int i = 0; i < axes; ++i) array.push_back(value);
    return array;
  };
  switch (key.form) {
    case KeyForm::number: return v;
    case KeyForm::vector: return per_axis(v);
    case KeyForm::direction: {
      json array = json::array({1.0});
      for (int i = 1; i < axes; ++i) array.push_back(0.0);
      return array;
    }
    case KeyForm::choice: return std::string(key.choices[0]);
    case KeyForm::flag: return true;
    case KeyForm::points: return json::parse("[[0, 0], [0.01, 0], [0, 0.01]]");
    case KeyForm::friction: return json{{"static", 0.5}, {"dynamic", 0.25}};
    case KeyForm::refused: break;
  }
  return nullptr;
}

// The effect with every declared key written (refused keys left out).
json full_example(const EffectDeclaration& declaration) {
  json effect = {{"type", std::string(declaration.type)}};
  for (std::size_t i = 0; i < declaration.keys.size(); ++i) {
    const EffectKey& key = declaration.keys[i];
    if (key.form != KeyForm::refused) effect[std::string(key.name)] = example_value(key, declaration.axes, static_cast<int>(i));
  }
  return effect;
}

template <int N>
std::string environment_text(const json& effect) {
  return json{{"device", N == 1 ? "hapkit3" : "haplink"}, {"effects", json::array({effect})}}.dump();
}

template <int N>
EnvironmentOf<N> compiled(const json& effect) {
  return compile_environment_of<N>(environment_text<N>(effect), "declared.json");
}

template <int N>
std::string load_error_of(const json& effect) {
  return test::input_error_of([&] { compiled<N>(effect); });
}

// The compiled value of `key` in the scene's first effect, per component.
template <int N, typename T>
std::vector<double> compiled_numbers(const EnvironmentOf<N>& environment, std::string_view name) {
  const T& effect = std::get<T>(environment.scene.effects.at(0));
  for (const KeyOf<T>& key : T::keys()) {
    if (key.key.name != name) continue;
    const double* numbers = read_numbers(key, effect);
    REQUIRE(numbers != nullptr);
    return std::vector<double>(numbers, numbers + component_count(key.key, N));
  }
  FAIL("no key " << name);
  return {};
}

template <int N, typename T>
void check_declaration() {
  constexpr EffectDeclaration declaration = declaration_of<T>();
  static constexpr auto keys = T::keys();
  CAPTURE(N);
  CAPTURE(declaration.type);
  REQUIRE(declaration.axes == N);

  {
    INFO("the declaration is consistent in itself");
    std::set<std::string_view> names;
    std::set<std::string_view> fields;
    for (const EffectKey& key : declaration.keys) {
      CAPTURE(key.name);
      CHECK(names.insert(key.name).second);
      if (!key.field.empty()) CHECK(fields.insert(key.field).second);
      if (key.slidable) CHECK((key.form == KeyForm::number || key.form == KeyForm::vector));
      if (!key.fallback_from.empty()) {
        const EffectKey* from = find_key(declaration, key.fallback_from);
        REQUIRE(from != nullptr);
        CHECK(from < &key);  // read before the key whose default it gives
        CHECK_FALSE(key.required);
      }
      if (key.form != KeyForm::refused && key.form != KeyForm::points && key.form != KeyForm::friction) {
        CHECK_FALSE(key.field.empty());  // Python shows every compiled value
      }
    }
    CHECK(gain_key(declaration) != nullptr);
    CHECK_FALSE(std::string_view(declaration.description).empty());
  }

  {
    INFO("the loader reads every declared key as written");
    const json effect = full_example(declaration);
    const EnvironmentOf<N> environment = compiled<N>(effect);
    REQUIRE(environment.scene.effects.size() == 1);
    const T& loaded = std::get<T>(environment.scene.effects[0]);
    for (std::size_t i = 0; i < declaration.keys.size(); ++i) {
      const KeyOf<T>& key = keys[i];
      CAPTURE(key.key.name);
      if (key.key.form == KeyForm::number || key.key.form == KeyForm::vector) {
        for (const double value : compiled_numbers<N, T>(environment, key.key.name)) {
          CHECK(value == doctest::Approx(0.01 * static_cast<double>(i + 1)));
        }
      }
      if (key.key.form == KeyForm::choice || key.key.form == KeyForm::flag) CHECK(*read_flag(key, loaded));
    }
  }

  {
    INFO("a required key left out is named, an optional one takes its declared default");
    for (const EffectKey& key : declaration.keys) {
      if (key.form == KeyForm::refused) continue;
      CAPTURE(key.name);
      json effect = full_example(declaration);
      effect.erase(std::string(key.name));
      if (key.required) {
        CHECK(load_error_of<N>(effect).find("missing required key \"" + std::string(key.name) + "\"") !=
              std::string::npos);
      } else if (key.form == KeyForm::number || key.form == KeyForm::vector) {
        const EnvironmentOf<N> environment = compiled<N>(effect);
        const double expected = key.fallback_from.empty()
                                    ? key.fallback_si
                                    : compiled_numbers<N, T>(environment, key.fallback_from).at(0);
        for (const double value : compiled_numbers<N, T>(environment, key.name)) CHECK(value == expected);
      } else {
        CHECK_NOTHROW(compiled<N>(effect));
      }
    }
  }

  {
    INFO("a number beyond its declared range is refused at its key");
    for (std::size_t i = 0; i < declaration.keys.size(); ++i) {
      const EffectKey& key = declaration.keys[i];
      if (key.form != KeyForm::number && key.form != KeyForm::vector) continue;
      CAPTURE(key.name);
      json effect = full_example(declaration);
      const double beyond = key.range.max * 10.0 + 1.0;
      json& value = effect[std::string(key.name)];
      if (value.is_array()) {
        for (json& component : value) component = beyond;
      } else {
        value = beyond;
      }
      const std::string error = load_error_of<N>(effect);
      CHECK(error.find("/effects/0/" + std::string(key.name)) != std::string::npos);
      CHECK(error.find("must be in") != std::string::npos);
    }
  }

  {
    INFO("an undeclared key is refused, and so is a refused one, with its reason");
    json effect = full_example(declaration);
    effect["undeclared_key"] = 1;
    CHECK(load_error_of<N>(effect).find("unknown key \"undeclared_key\"") != std::string::npos);
    for (const EffectKey& key : declaration.keys) {
      if (key.form != KeyForm::refused) continue;
      CAPTURE(key.name);
      json with_refused = full_example(declaration);
      with_refused[std::string(key.name)] = 1;
      CHECK(load_error_of<N>(with_refused).find(std::string(key.description)) != std::string::npos);
    }
  }

  {
    INFO("the schema lists the declared keys, and the committed schema is the generated one");
    const std::string def_name = "effect_" + std::to_string(N) + "d_" + std::string(declaration.type);
    const nlohmann::ordered_json generated = effect_schemas().at(def_name);
    std::set<std::string> properties;
    for (const auto& [name, value] : generated.at("properties").items()) properties.insert(name);
    std::set<std::string> expected{"type", "enabled"};
    std::set<std::string> required{"type"};
    for (const EffectKey& key : declaration.keys) {
      if (key.form == KeyForm::refused) continue;
      expected.insert(std::string(key.name));
      if (key.required) required.insert(std::string(key.name));
    }
    CHECK(properties == expected);
    CHECK(generated.at("required").get<std::set<std::string>>() == required);
    CHECK(generated.at("additionalProperties") == false);

    std::ifstream file(test::source_path("schemas/environment.schema.json"));
    const json committed = json::parse(file);
    REQUIRE(committed.at("$defs").contains(def_name));
    CHECK_MESSAGE(json::parse(generated.dump()) == committed.at("$defs").at(def_name),
                  "schemas/environment.schema.json is stale: python3 schemas/generate_schemas.py");
  }

  {
    INFO("the live view offers a slider for each slidable key, per component");
    const json effect = full_example(declaration);
    const EnvironmentOf<N> environment = compiled<N>(effect);
    const json document = json::parse(environment_text<N>(effect));
    std::vector<std::string> offered;
    for (const LiveParameter& p : live_parameters<N>(document, environment.scene)) {
      if (p.effect == 0) offered.push_back(p.parameter);
    }
    std::vector<std::string> expected;
    for (const EffectKey& key : declaration.keys) {
      if (!key.slidable) continue;
      const int components = component_count(key, N);
      for (int i = 0; i < components; ++i) {
        expected.push_back(std::string(key.name) + (components > 1 ? "/" + std::to_string(i) : ""));
      }
    }
    CHECK(offered == expected);
  }
}

}  // namespace effect_declarations_test

TEST_CASE("effect declarations: every built-in effect of every N agrees with the loader, the schema and the sliders") {
  using namespace effect_declarations_test;
#define HAPSCENE_CHECK_DECLARATIONS(N) \
  for_each_builtin<N>([]<typename T>(std::type_identity<T>) { check_declaration<N, T>(); });
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_CHECK_DECLARATIONS)
#undef HAPSCENE_CHECK_DECLARATIONS
}
