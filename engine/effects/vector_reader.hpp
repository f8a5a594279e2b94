#pragma once
// Reading the vector forms of an environment's effects, for the kinds with more than one
// axis (today the planar one): vectors [x, y] (each a number in SI or a string with a unit,
// "10 mm"), directions, point lists, a shape's solid side and friction. Errors carry the file and the JSON pointer down to the component:
// "env.json: /effects/2/center/1: must be in [-1000, 1000] m, got 5000 m".
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/effects/planar/proxy_state.hpp"

namespace hapscene {

// A vector of `count` components [x, y, ...] of `quantity`, each within `component`, into
// out[0 .. count); false (out untouched) when the key is absent.
bool read_components(ObjectReader& reader, std::string_view key, Quantity quantity, Range component, int count,
                     double* out);
// A required vector [x, y] of `quantity`, each component within `component`.
Vec2 read_vector(ObjectReader& reader, std::string_view key, Quantity quantity, Range component);
// The same, or `fallback` when the key is absent.
Vec2 read_vector_or(ObjectReader& reader, std::string_view key, Quantity quantity, Vec2 fallback,
                    Range component);
// A required direction [dx, dy] (dimensionless, any non-zero length), returned as the unit
// vector (dx, dy) / sqrt(dx * dx + dy * dy), computed by unit_vector (engine/base/axes.hpp)
// so that components too small (or large) for their squares still give their direction.
Vec2 read_direction(ObjectReader& reader, std::string_view key);
// A required list of at least `min_count` and at most `max_count` points [[x, y], ...].
std::vector<Vec2> read_points(ObjectReader& reader, std::string_view key, Range component,
                              std::size_t min_count, std::size_t max_count);
// "solid": "inside" (the shape is solid) or "outside" (all but the shape is: a cage).
// Required. True for "inside".
bool read_solid_inside(ObjectReader& reader);
// An optional "friction": {"static": mu_s, "dynamic": mu_d} with mu_s >= mu_d; zeros when
// absent.
FrictionCoefficients read_friction(ObjectReader& reader);

// "[x, y]": the written form of a vector of `count` components (messages, schemas).
std::string bracket_form(int count);

}  // namespace hapscene
