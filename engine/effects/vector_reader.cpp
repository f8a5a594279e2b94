#include "engine/effects/vector_reader.hpp"

#include <cmath>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"

namespace hapscene {
namespace {

// Fails at `pointer` (an element below a key, such as "/effects/3/points/2").
[[noreturn]] void fail_at(const ObjectReader& reader, const std::string& pointer,
                          const std::string& message) {
  throw InputError(located_message(reader.file(), pointer, message));
}

// "a 2-D vector [x, y] of lengths in m (or strings with a unit)": what a vector key takes.
std::string vector_form(Quantity quantity, int count) {
  const std::string unit(si_unit(quantity));
  const std::string head = "a " + std::to_string(count) + "-D vector " + bracket_form(count) + " of ";
  if (unit.empty()) return head + "numbers";
  return head + std::string(quantity_name(quantity)) + "s in " + unit + " (or strings with a unit)";
}

// Reads one [x, y] value found at `pointer` (its components at pointer/0, pointer/1, ...)
// into out[0 .. count).
void vector_at(const ObjectReader& parent, const nlohmann::json& value, const std::string& pointer,
               Quantity quantity, Range component, int count, double* out) {
  if (!value.is_array() || value.size() != static_cast<std::size_t>(count)) {
    std::string got = json_type_name(value);
    if (value.is_array()) got = "an array of " + std::to_string(value.size());
    std::string message = "expected " + vector_form(quantity, count) + ", got " + got;
    // A 1-D scene's form of the key (a single number or string) in a scene of more axes.
    if (value.is_number() || value.is_string()) {
      message += " (a 1-D form: a " + std::to_string(count) + "-D scene takes " + bracket_form(count) + ")";
    }
    fail_at(parent, pointer, message);
  }
  nlohmann::json components = nlohmann::json::object();
  for (int i = 0; i < count; ++i) components[std::to_string(i)] = value[static_cast<std::size_t>(i)];
  ObjectReader holder(components, pointer, parent.file(), parent.base_dir());
  for (int i = 0; i < count; ++i) out[i] = holder.quantity(std::to_string(i), quantity, component);
}

Vec2 vector_at(const ObjectReader& parent, const nlohmann::json& value, const std::string& pointer,
               Quantity quantity, Range component) {
  Vec2 result;
  vector_at(parent, value, pointer, quantity, component, 2, result.value);
  return result;
}

}  // namespace

std::string bracket_form(int count) {
  std::string form = "[";
  for (int i = 0; i < count; ++i) form += std::string(i ? ", " : "") + kAxisNames[i];
  return form + "]";
}


bool read_components(ObjectReader& reader, std::string_view key, Quantity quantity, Range component, int count,
                     double* out) {
  const nlohmann::json* value = reader.get(key);
  if (value == nullptr) return false;
  vector_at(reader, *value, reader.pointer_to(key), quantity, component, count, out);
  return true;
}

Vec2 read_vector(ObjectReader& reader, std::string_view key, Quantity quantity, Range component) {
  Vec2 result;
  if (!read_components(reader, key, quantity, component, 2, result.value)) reader.fail_missing(key);
  return result;
}

Vec2 read_vector_or(ObjectReader& reader, std::string_view key, Quantity quantity, Vec2 fallback,
                    Range component) {
  Vec2 result;
  return read_components(reader, key, quantity, component, 2, result.value) ? result : fallback;
}

Vec2 read_direction(ObjectReader& reader, std::string_view key) {
  const Vec2 raw = read_vector(reader, key, Quantity::dimensionless, ranges::kDirectionComponent);
  Vec2 unit;
  if (!unit_vector(raw, &unit)) reader.fail(key, "must not be the zero vector: it gives the direction");
  return unit;
}

std::vector<Vec2> read_points(ObjectReader& reader, std::string_view key, Range component,
                              std::size_t min_count, std::size_t max_count) {
  const nlohmann::json* value = reader.get(key);
  if (value == nullptr) reader.fail_missing(key);
  if (!value->is_array()) {
    reader.fail(key, "expected an array of points [[x, y], ...], got " + json_type_name(*value));
  }
  if (value->size() < min_count || value->size() > max_count) {
    reader.fail(key, "expected " + std::to_string(min_count) + " to " + std::to_string(max_count) +
                         " points, got " + std::to_string(value->size()));
  }
  std::vector<Vec2> points;
  points.reserve(value->size());
  const std::string pointer = reader.pointer_to(key);
  for (std::size_t i = 0; i < value->size(); ++i) {
    points.push_back(vector_at(reader, (*value)[i], json_pointer_append(pointer, i),
                               Quantity::length_m, component));
  }
  return points;
}

bool read_solid_inside(ObjectReader& reader) {
  return reader.choice("solid", {"inside", "outside"}) == "inside";
}

FrictionCoefficients read_friction(ObjectReader& reader) {
  const nlohmann::json* value = reader.get("friction");
  if (value == nullptr) return {};
  ObjectReader block(*value, reader.pointer_to("friction"), reader.file(), reader.base_dir());
  FrictionCoefficients friction;
  friction.static_mu = block.quantity("static", Quantity::dimensionless, ranges::kFrictionCoefficient);
  friction.dynamic_mu = block.quantity("dynamic", Quantity::dimensionless, ranges::kFrictionCoefficient);
  if (friction.dynamic_mu > friction.static_mu) {
    block.fail("dynamic", "must not exceed the static coefficient (" + format_number(friction.static_mu) +
                              "), got " + format_number(friction.dynamic_mu));
  }
  block.finish();
  return friction;
}

}  // namespace hapscene
