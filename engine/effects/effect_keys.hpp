#pragma once
// One declaration per built-in effect. Each effect type lists its JSON keys once, in
// keys(): each key's form, quantity, range, default, whether the live view may slide it
// and the name of its compiled value. The loader reads an effect through that list
// (parse_declared, engine/effects/declared_parse.hpp), and the live view's sliders, the
// load warnings, the Python bindings and `hapscene schema` read the same list, so a key is
// written in one place. tests/effects/effect_declarations_test.cpp checks every
// declaration against the parser, the schema, the sliders and Python.
//
// An effect type declares, beside its force law:
//   static constexpr const char* kType;         // its "type" in files
//   static constexpr int kAxes;                 // the N of the scenes it renders in
//   static constexpr const char* kDescription;  // one line for people and the schema
//   static constexpr auto keys();               // std::array of KeyOf<Type>, in reading order
// and optionally static void finish_parse(ObjectReader&, Type&), called after every key
// is read (derived values, checks across keys).
#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "engine/base/axes.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/base/units.hpp"

namespace hapscene {

class ObjectReader;

// How a key's value is written.
enum class KeyForm {
  number,     // a quantity: a number (SI) or a string with a unit
  vector,     // one quantity per axis, [x, y] (a number when the effect has one axis)
  direction,  // one number per axis, not all zero, compiled to the unit vector
  choice,     // one of two strings; the first compiles to true
  flag,       // true or false
  points,     // a list of [x, y] (between min_items and max_items), read by the effect's own function
  friction,   // {"static": mu_s, "dynamic": mu_d}, read by the effect's own function
  refused,    // a key of another form of the effect: refused, `description` says why
};

// The form's name, as tools show it ("number", "vector", ...).
constexpr std::string_view form_name(KeyForm form) {
  switch (form) {
    case KeyForm::number: return "number";
    case KeyForm::vector: return "vector";
    case KeyForm::direction: return "direction";
    case KeyForm::choice: return "choice";
    case KeyForm::flag: return "flag";
    case KeyForm::points: return "points";
    case KeyForm::friction: return "friction";
    case KeyForm::refused: return "refused";
  }
  return "";
}

// One key of an effect, as every tool sees it. Built from key() and the setters below
// (each returns a changed copy), so a declaration reads as a sentence:
//   key("radius", KeyForm::number, Quantity::length_m, ranges::kRadius_m).needed().slides().as("radius_m")
struct EffectKey {
  std::string_view name{};
  KeyForm form{KeyForm::number};
  Quantity quantity{Quantity::dimensionless};
  Range range{};                          // each component's (number, vector, points)
  bool required{};
  double fallback_si{};                   // optional: the default (flag: 0 or 1) ...
  std::string_view fallback_from{};       // ... or another key's value
  std::array<std::string_view, 2> choices{};
  int min_items{};                        // points: how many
  int max_items{};
  bool slidable{};                        // the live view offers a slider (per component)
  bool gain{};                            // at zero the effect never acts (a load warning)
  std::string_view field{};               // the compiled value's name: "stiffness_N_per_m"
  std::string_view description{};         // for the schema (refused: the reason)

  constexpr EffectKey needed() const { EffectKey k = *this; k.required = true; return k; }
  constexpr EffectKey or_default(double si) const { EffectKey k = *this; k.fallback_si = si; return k; }
  constexpr EffectKey or_value_of(std::string_view other) const { EffectKey k = *this; k.fallback_from = other; return k; }
  constexpr EffectKey slides() const { EffectKey k = *this; k.slidable = true; return k; }
  constexpr EffectKey is_gain() const { EffectKey k = *this; k.gain = true; return k; }
  constexpr EffectKey as(std::string_view compiled) const { EffectKey k = *this; k.field = compiled; return k; }
  constexpr EffectKey says(std::string_view text) const { EffectKey k = *this; k.description = text; return k; }
  constexpr EffectKey one_of(std::string_view first, std::string_view second) const {
    EffectKey k = *this;
    k.choices = {first, second};
    return k;
  }
  constexpr EffectKey items(int least, int most) const {
    EffectKey k = *this;
    k.min_items = least;
    k.max_items = most;
    return k;
  }
};

// A key of `form` named `name`, of `quantity` within `range` (optional, not slidable, not
// shown, until the setters say otherwise).
constexpr EffectKey key(std::string_view name, KeyForm form, Quantity quantity = Quantity::dimensionless,
                        Range range = {}) {
  EffectKey k;
  k.name = name;
  k.form = form;
  k.quantity = quantity;
  k.range = range;
  return k;
}

// A key bound to where an effect of type E keeps its compiled value.
template <typename E>
struct KeyOf {
  EffectKey key;
  double* (*numbers)(E&) = nullptr;         // number, vector, direction: the first component
  bool* (*flag)(E&) = nullptr;              // choice, flag
  void (*read)(ObjectReader&, E&) = nullptr;         // points, friction: reads the key
  void (*check)(ObjectReader&, const E&) = nullptr;  // after the key: a check across keys
};

// The first number of a compiled value of any N, for a key's slot:
// [](Spring& e) { return numbers_of(e.center_m); }.
constexpr double* numbers_of(double& value) { return &value; }
template <int N>
constexpr double* numbers_of(AxisVector<N>& value) { return value.value; }

// The compiled numbers of `key` in `effect` (null for a key without numbers). Tools only
// read them; the slots take a mutable effect because the parser writes through them.
template <typename E>
const double* read_numbers(const KeyOf<E>& key, const E& effect) {
  return key.numbers != nullptr ? key.numbers(const_cast<E&>(effect)) : nullptr;
}
template <typename E>
const bool* read_flag(const KeyOf<E>& key, const E& effect) {
  return key.flag != nullptr ? key.flag(const_cast<E&>(effect)) : nullptr;
}

// The keys most effects share.
namespace effect_keys {

constexpr EffectKey stiffness(std::string_view description = "K") {
  return key("stiffness", KeyForm::number, Quantity::stiffness_N_per_m, ranges::kStiffness_N_per_m)
      .needed().slides().is_gain().as("stiffness_N_per_m").says(description);
}
constexpr EffectKey damping(std::string_view description = "B") {
  return key("damping", KeyForm::number, Quantity::damping_N_s_per_m, ranges::kDamping_N_s_per_m)
      .needed().slides().is_gain().as("damping_N_s_per_m").says(description);
}
// A required place (a number in 1-D, a point [x, y] in 2-D: `form` number or vector)
// named `name`, compiled as `field`.
constexpr EffectKey place(std::string_view name, std::string_view field, KeyForm form,
                          std::string_view description = "") {
  return key(name, form, Quantity::length_m, ranges::kPosition_m).needed().slides().as(field).says(description);
}
// The same, optional, at the origin when left out.
constexpr EffectKey place_or_origin(std::string_view name, std::string_view field, KeyForm form,
                                    std::string_view description = "") {
  return key(name, form, Quantity::length_m, ranges::kPosition_m).or_default(0.0).slides().as(field).says(description);
}
// A required direction [dx, dy], compiled to the unit vector.
constexpr EffectKey direction(std::string_view name, std::string_view description) {
  return key(name, KeyForm::direction, Quantity::dimensionless, ranges::kDirectionComponent)
      .needed().as(name).says(description);
}
// "solid": one of two sides, compiled to whether the first is solid.
constexpr EffectKey solid(std::string_view first, std::string_view second, std::string_view field) {
  return key("solid", KeyForm::choice).needed().one_of(first, second).as(field);
}
// The keys of the damping bands (1-D, and across the bands in 2-D).
constexpr EffectKey band_width() {
  return key("width", KeyForm::number, Quantity::length_m, ranges::kFieldWidth_m)
      .needed().slides().as("width_m").says("each field's width");
}
constexpr EffectKey band_spacing() {
  return key("spacing", KeyForm::number, Quantity::length_m, ranges::kLength_m)
      .or_value_of("width").slides().as("spacing_m").says("the gap between fields (default: the width)");
}
constexpr EffectKey band_offset() {
  return key("offset", KeyForm::number, Quantity::length_m, ranges::kPosition_m)
      .or_default(0.0).slides().as("offset_m").says("where the first field starts");
}
// A key of another form of the effect, refused with `reason`.
constexpr EffectKey refused(std::string_view name, std::string_view reason) {
  return key(name, KeyForm::refused).says(reason);
}

}  // namespace effect_keys

// What a tool needs of one effect type, without the type.
struct EffectDeclaration {
  std::string_view type{};
  std::string_view description{};
  int axes{};
  std::span<const EffectKey> keys{};
};

namespace detail {
template <typename E>
inline constexpr auto kPlainKeys = [] {
  constexpr auto keys = E::keys();
  std::array<EffectKey, keys.size()> plain{};
  for (std::size_t i = 0; i < keys.size(); ++i) plain[i] = keys[i].key;
  return plain;
}();
}  // namespace detail

template <typename E>
constexpr EffectDeclaration declaration_of() {
  return {E::kType, E::kDescription, E::kAxes, detail::kPlainKeys<E>};
}

// How many numbers a key's compiled value holds: one per axis for vectors and directions.
constexpr int component_count(const EffectKey& key, int axes) {
  return key.form == KeyForm::vector || key.form == KeyForm::direction ? axes : 1;
}

// The declared key named `name` of `declaration`, or null.
constexpr const EffectKey* find_key(const EffectDeclaration& declaration, std::string_view name) {
  for (const EffectKey& key : declaration.keys) {
    if (key.name == name) return &key;
  }
  return nullptr;
}

// The key whose zero means the effect never acts (its stiffness or damping), or null.
constexpr const EffectKey* gain_key(const EffectDeclaration& declaration) {
  for (const EffectKey& key : declaration.keys) {
    if (key.gain) return &key;
  }
  return nullptr;
}

}  // namespace hapscene
