#pragma once
// Reads one JSON object of an environment or profile file, key by key, with errors that
// name the file and the JSON pointer: "wall.json: /effects/1/stiffness: must be >= 0".
// Every key read is remembered, so finish() can refuse keys nobody asked for and suggest
// the nearest valid one.
#include <initializer_list>
#include <string>
#include <utility>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/range.hpp"
#include "engine/base/units.hpp"

namespace hapscene {

class ObjectReader {
 public:
  // `file` names the source in messages; `pointer` is this object's JSON pointer ("" for
  // the root, where a string "$schema" is accepted and ignored); relative paths inside it
  // are taken from `base_dir`. Throws InputError when `value` is not an object.
  ObjectReader(const nlohmann::json& value, std::string pointer, std::string file,
               std::string base_dir = ".");

  // A required quantity: a number (SI) or a string with a unit of `quantity`.
  double quantity(std::string_view key, Quantity quantity, Bound bound = Bound::any);
  // The same, or `fallback` when the key is absent.
  double quantity_or(std::string_view key, Quantity quantity, double fallback,
                     Bound bound = Bound::any);
  // The same within a finite range.
  double quantity(std::string_view key, Quantity quantity, Range range);
  double quantity_or(std::string_view key, Quantity quantity, double fallback, Range range);
  // A required pair [low, high] of quantities with low < high, each end within `ends`.
  std::pair<double, double> range(std::string_view key, Quantity quantity);
  std::pair<double, double> range(std::string_view key, Quantity quantity, Range ends);
  // A required whole number in [min, max], and one with a fallback.
  long long integer(std::string_view key, long long min, long long max);
  long long integer_or(std::string_view key, long long min, long long max, long long fallback);
  // A required string, and one with a fallback.
  std::string string(std::string_view key);
  std::string string_or(std::string_view key, std::string fallback);
  // A string that must be one of `options`; `fallback` when absent (empty: required).
  std::string choice(std::string_view key, std::initializer_list<std::string_view> options,
                     std::string fallback = {});
  // The raw value, or nullptr when absent. Marks the key as read.
  const nlohmann::json* get(std::string_view key);
  bool has(std::string_view key) const;
  // A required sub-object "key", read by `parse(ObjectReader&)` (absent: fail_missing).
  template <typename Parse>
  auto part(std::string_view key, Parse parse) {
    const nlohmann::json* value = get(key);
    if (value == nullptr) fail_missing(key);
    ObjectReader reader(*value, pointer_to(key), file());
    return parse(reader);
  }

  // Refuses any key that was never read, suggesting the nearest expected key.
  void finish() const;

  // Throws InputError located at `key` (or at this object when key is empty).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  // Throws for a required `key` that is absent: at a key of the object that looks like a
  // misspelling of it, `unknown key "stifness" (did you mean "stiffness"?)`; else
  // `missing required key "stiffness"` at this object.
  [[noreturn]] void fail_missing(std::string_view key) const;

  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& base_dir() const { return base_dir_; }
  std::string pointer_to(std::string_view key) const;

 private:
  double to_quantity(std::string_view key, const nlohmann::json& value, Quantity quantity,
                     Bound bound) const;
  void check_range(std::string_view key, double value_si, Quantity quantity, Range range) const;

  const nlohmann::json& object_;
  std::string pointer_;
  std::string file_;
  std::string base_dir_;
  std::vector<std::string> read_keys_;
};

// A number as messages show it: shortest form, up to 10 significant digits.
std::string format_number(double value);

// "file: /pointer: message", or "file: message" for the root.
std::string located_message(const std::string& file, const std::string& pointer,
                            const std::string& message);

}  // namespace hapscene
