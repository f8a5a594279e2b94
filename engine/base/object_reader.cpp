#include "engine/base/object_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"

namespace hapscene {
std::string format_number(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

std::string located_message(const std::string& file, const std::string& pointer,
                            const std::string& message) {
  if (pointer.empty()) return file + ": " + message;
  return file + ": " + pointer + ": " + message;
}

ObjectReader::ObjectReader(const nlohmann::json& value, std::string pointer, std::string file,
                           std::string base_dir)
    : object_(value), pointer_(std::move(pointer)), file_(std::move(file)), base_dir_(std::move(base_dir)) {
  if (!object_.is_object()) {
    throw InputError(located_message(file_, pointer_,
                                     "expected an object, got " + json_type_name(object_)));
  }
  // A file's root may name its JSON Schema ("$schema": a URI, for editors; see schemas/):
  // a string, otherwise ignored. Nowhere else is it a key.
  if (pointer_.empty()) {
    const auto schema = object_.find("$schema");
    if (schema != object_.end()) {
      if (!schema->is_string()) {
        fail("$schema", "expected a string (the URI of this file's JSON Schema), got " + json_type_name(*schema));
      }
      read_keys_.emplace_back("$schema");
    }
  }
}

std::string ObjectReader::pointer_to(std::string_view key) const {
  return key.empty() ? pointer_ : json_pointer_append(pointer_, key);
}

void ObjectReader::fail(std::string_view key, const std::string& message) const {
  throw InputError(located_message(file_, pointer_to(key), message));
}

bool ObjectReader::has(std::string_view key) const { return object_.contains(key); }

const nlohmann::json* ObjectReader::get(std::string_view key) {
  if (std::find(read_keys_.begin(), read_keys_.end(), key) == read_keys_.end()) {
    read_keys_.emplace_back(key);
  }
  const auto found = object_.find(key);
  return found == object_.end() ? nullptr : &*found;
}

double ObjectReader::to_quantity(std::string_view key, const nlohmann::json& value,
                                 Quantity quantity, Bound bound) const {
  const std::string unit(si_unit(quantity));
  double value_si = 0.0;
  if (value.is_number()) {
    value_si = value.get<double>();
    if (!std::isfinite(value_si)) fail(key, "must be a finite number");
  } else if (value.is_string()) {
    const QuantityParse parsed = parse_quantity_as(value.get<std::string>(), quantity);
    if (!parsed.ok) fail(key, parsed.error);
    value_si = parsed.value_si;
  } else {
    std::string expected = "expected a " + std::string(quantity_name(quantity));
    if (!unit.empty()) expected += " in " + unit + " or a string with a unit";
    fail(key, expected + ", got " + json_type_name(value));
  }
  const std::string shown = format_number(value_si) + (unit.empty() ? "" : " " + unit);
  if (bound == Bound::non_negative && value_si < 0.0) fail(key, "must be >= 0, got " + shown);
  if (bound == Bound::positive && value_si <= 0.0) fail(key, "must be > 0, got " + shown);
  return value_si;
}

void ObjectReader::check_range(std::string_view key, double value_si, Quantity quantity, Range range) const {
  const bool below = range.min_excluded ? !(value_si > range.min) : !(value_si >= range.min);
  if (!below && value_si <= range.max) return;
  const std::string unit(si_unit(quantity));
  const std::string suffix = unit.empty() ? "" : " " + unit;
  const std::string shown = format_number(value_si) + suffix;
  // Below a lower bound of 0, or not positive where the range is, the words Bound gives.
  if (below && range.min == 0.0 && !range.min_excluded) fail(key, "must be >= 0, got " + shown);
  if (below && range.min >= 0.0 && value_si <= 0.0) fail(key, "must be > 0, got " + shown);
  fail(key, "must be in " + std::string(range.min_excluded ? "(" : "[") + format_number(range.min) + ", " +
                format_number(range.max) + "]" + suffix + ", got " + shown);
}

double ObjectReader::quantity(std::string_view key, Quantity quantity, Range range) {
  const double value_si = this->quantity(key, quantity);
  check_range(key, value_si, quantity, range);
  return value_si;
}

double ObjectReader::quantity_or(std::string_view key, Quantity quantity, double fallback, Range range) {
  if (!has(key)) {
    get(key);
    return fallback;
  }
  return this->quantity(key, quantity, range);
}

double ObjectReader::quantity(std::string_view key, Quantity quantity, Bound bound) {
  const nlohmann::json* value = get(key);
  if (value == nullptr) fail_missing(key);
  return to_quantity(key, *value, quantity, bound);
}

double ObjectReader::quantity_or(std::string_view key, Quantity quantity, double fallback,
                                 Bound bound) {
  const nlohmann::json* value = get(key);
  return value == nullptr ? fallback : to_quantity(key, *value, quantity, bound);
}

std::pair<double, double> ObjectReader::range(std::string_view key, Quantity quantity) {
  const nlohmann::json* value = get(key);
  if (value == nullptr) fail_missing(key);
  if (!value->is_array() || value->size() != 2) {
    fail(key, "expected [low, high] as an array of two " + std::string(quantity_name(quantity)) +
                  " values, got " + json_type_name(*value));
  }
  const std::string pointer = pointer_to(key);
  // Read both ends as keys "0" and "1", so their errors carry ".../workspace/0".
  const nlohmann::json ends = nlohmann::json::object({{"0", (*value)[0]}, {"1", (*value)[1]}});
  ObjectReader holder(ends, pointer, file_);
  const double low = holder.quantity("0", quantity);
  const double high = holder.quantity("1", quantity);
  if (!(low < high)) fail(key, "low must be below high");
  return {low, high};
}

std::pair<double, double> ObjectReader::range(std::string_view key, Quantity quantity, Range ends) {
  const auto [low, high] = range(key, quantity);
  // Each end is checked at its own pointer (".../workspace/0"), as range() reads them.
  const ObjectReader holder(nlohmann::json::object(), pointer_to(key), file_);
  holder.check_range("0", low, quantity, ends);
  holder.check_range("1", high, quantity, ends);
  return {low, high};
}

long long ObjectReader::integer(std::string_view key, long long min, long long max) {
  const nlohmann::json* value = get(key);
  if (value == nullptr) fail_missing(key);
  const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
  // Echo the number as written: an unsigned above 2^63 - 1 must not read back as negative.
  if (value->is_number_unsigned()) {
    const auto number = value->get<std::uint64_t>();
    const bool below = min > 0 && number < static_cast<std::uint64_t>(min);
    const bool above = max < 0 || number > static_cast<std::uint64_t>(max);
    if (below || above) fail(key, "must be in " + range + ", got " + std::to_string(number));
    return static_cast<long long>(number);
  }
  if (value->is_number_integer()) {
    const auto number = value->get<long long>();
    if (number < min || number > max) fail(key, "must be in " + range + ", got " + std::to_string(number));
    return number;
  }
  // "1e6" is a whole number too; 1.5 is not.
  if (value->is_number_float()) {
    const double number = value->get<double>();
    char shown[32];
    const auto written = std::to_chars(shown, shown + sizeof shown, number);
    const std::string text(shown, written.ptr);
    if (number != std::floor(number)) fail(key, "expected a whole number, got " + text);
    if (number < static_cast<double>(min) || number > static_cast<double>(max)) {
      fail(key, "must be in " + range + ", got " + text);
    }
    return static_cast<long long>(number);
  }
  fail(key, "expected a whole number, got " + json_type_name(*value));
}

long long ObjectReader::integer_or(std::string_view key, long long min, long long max,
                                  long long fallback) {
  if (!has(key)) {
    get(key);
    return fallback;
  }
  return integer(key, min, max);
}

std::string ObjectReader::string(std::string_view key) {
  const nlohmann::json* value = get(key);
  if (value == nullptr) fail_missing(key);
  if (!value->is_string()) fail(key, "expected a string, got " + json_type_name(*value));
  return value->get<std::string>();
}

std::string ObjectReader::string_or(std::string_view key, std::string fallback) {
  return has(key) ? string(key) : (get(key), std::move(fallback));
}

std::string ObjectReader::choice(std::string_view key,
                                 std::initializer_list<std::string_view> options,
                                 std::string fallback) {
  if (!has(key) && !fallback.empty()) {
    get(key);
    return fallback;
  }
  const std::string value = string(key);
  if (std::find(options.begin(), options.end(), value) != options.end()) return value;
  std::string list;
  for (const std::string_view option : options) {
    list += (list.empty() ? "\"" : ", \"") + std::string(option) + "\"";
  }
  std::string message = "\"" + value + "\" is not one of " + list;
  const std::string suggestion = nearest_name(value, options);
  if (!suggestion.empty()) message += " (did you mean \"" + suggestion + "\"?)";
  fail(key, message);
}

void ObjectReader::fail_missing(std::string_view key) const {
  // Only near misses (a key the reader has not asked for yet may be another expected one:
  // "max" is not a misspelled "min"): one edit in a name of 4 or 5 bytes, two from 6 on.
  const std::size_t near_edits = key.size() >= 6 ? 2 : (key.size() >= 4 ? 1 : 0);
  for (const auto& [written, value] : object_.items()) {
    if (std::find(read_keys_.begin(), read_keys_.end(), written) != read_keys_.end()) continue;
    if (near_edits > 0 && edit_distance(written, key) <= near_edits) {
      fail(written, "unknown key \"" + written + "\" (did you mean \"" + std::string(key) + "\"?)");
    }
  }
  fail("", "missing required key \"" + std::string(key) + "\"");
}

void ObjectReader::finish() const {
  for (const auto& [key, value] : object_.items()) {
    if (std::find(read_keys_.begin(), read_keys_.end(), key) != read_keys_.end()) continue;
    std::string message = "unknown key \"" + key + "\"";
    const std::string suggestion = nearest_name(key, read_keys_);
    if (!suggestion.empty()) message += " (did you mean \"" + suggestion + "\"?)";
    fail(key, message);
  }
}

}  // namespace hapscene
