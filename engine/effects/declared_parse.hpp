#pragma once
// Reading an effect through its declaration (engine/effects/effect_keys.hpp): every key of
// E::keys() in order, each checked against its declared quantity and range, defaults
// filled in, then E::finish_parse when the type has one. The caller reads "type" and
// "enabled" and calls reader.finish(), which refuses keys nobody declared.
#include <string>
#include <type_traits>

#include "engine/base/axes.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/effects/vector_reader.hpp"

namespace hapscene {

namespace detail {

// The value of the already read key `name` (a number's), for a default taken from it.
template <typename E, std::size_t Count>
double declared_value(const std::array<KeyOf<E>, Count>& keys, std::string_view name, E& effect) {
  for (const KeyOf<E>& key : keys) {
    if (key.key.name == name && key.numbers != nullptr) return *key.numbers(effect);
  }
  return 0.0;
}

template <typename E, std::size_t Count>
void read_declared_key(ObjectReader& reader, const KeyOf<E>& bound, const std::array<KeyOf<E>, Count>& keys,
                       E& effect) {
  const EffectKey& key = bound.key;
  switch (key.form) {
    case KeyForm::number:
    case KeyForm::vector: {
      double* out = bound.numbers(effect);
      if (key.form == KeyForm::vector && E::kAxes > 1) {
        if (!read_components(reader, key.name, key.quantity, key.range, E::kAxes, out)) {
          if (key.required) reader.fail_missing(key.name);
          for (int i = 0; i < E::kAxes; ++i) out[i] = key.fallback_si;
        }
      } else if (key.required) {
        *out = reader.quantity(key.name, key.quantity, key.range);
      } else {
        const double fallback =
            key.fallback_from.empty() ? key.fallback_si : declared_value(keys, key.fallback_from, effect);
        *out = reader.quantity_or(key.name, key.quantity, fallback, key.range);
      }
      break;
    }
    case KeyForm::direction: {
      if constexpr (E::kAxes > 1) {
        AxisVector<E::kAxes> raw;
        if (!read_components(reader, key.name, Quantity::dimensionless, key.range, E::kAxes, raw.value)) {
          reader.fail_missing(key.name);
        }
        AxisVector<E::kAxes> unit;
        if (!unit_vector(raw, &unit)) reader.fail(key.name, "must not be the zero vector: it gives the direction");
        for (int i = 0; i < E::kAxes; ++i) bound.numbers(effect)[i] = unit[i];
      }
      break;
    }
    case KeyForm::choice:
      *bound.flag(effect) = reader.choice(key.name, {key.choices[0], key.choices[1]}) == key.choices[0];
      break;
    case KeyForm::flag:
      if (const nlohmann::json* value = reader.get(key.name)) {
        if (!value->is_boolean()) reader.fail(key.name, "expected a boolean, got " + json_type_name(*value));
        *bound.flag(effect) = value->get<bool>();
      } else {
        *bound.flag(effect) = key.fallback_si != 0.0;
      }
      break;
    case KeyForm::refused:
      if (reader.has(key.name)) {
        reader.get(key.name);
        reader.fail(key.name, std::string(key.description));
      }
      break;
    case KeyForm::points:
    case KeyForm::friction:
      bound.read(reader, effect);
      break;
  }
  if (bound.check != nullptr) bound.check(reader, effect);
}

// What the reader does not do, refused when the declaration is compiled: a direction or a
// default taken from another key's value on a vector of more than one axis.
template <typename E>
constexpr bool readable_declaration() {
  for (const KeyOf<E>& bound : E::keys()) {
    const EffectKey& key = bound.key;
    if (key.form == KeyForm::direction && E::kAxes < 2) return false;
    if (key.form == KeyForm::vector && E::kAxes > 1 && !key.fallback_from.empty()) return false;
    if ((key.form == KeyForm::number || key.form == KeyForm::vector || key.form == KeyForm::direction) &&
        bound.numbers == nullptr) {
      return false;
    }
    if ((key.form == KeyForm::choice || key.form == KeyForm::flag) && bound.flag == nullptr) return false;
    if ((key.form == KeyForm::points || key.form == KeyForm::friction) && bound.read == nullptr) return false;
  }
  return true;
}

}  // namespace detail

// The effect of type E that `reader`'s object declares (throws InputError at the key).
template <typename E>
E parse_declared(ObjectReader& reader) {
  static_assert(detail::readable_declaration<E>(), "a key of this declaration has a form the reader cannot read");
  static constexpr auto keys = E::keys();
  E effect{};
  for (const KeyOf<E>& key : keys) detail::read_declared_key(reader, key, keys, effect);
  if constexpr (requires { E::finish_parse(reader, effect); }) E::finish_parse(reader, effect);
  return effect;
}

}  // namespace hapscene
