#pragma once
// The values the harness accepts for what a user can set: the virtual hand, the sensor
// noise, the free scenario's start, and the points of an open-loop probe. The command
// line (engine/cli/option_definitions.hpp builds its options from these) and test specs
// (their "options" and "forces") check against the same ranges, so a spec cannot ask
// for what `validate` or `probe` would refuse.
#include <string>
#include <string_view>

#include "engine/base/units.hpp"

namespace hapscene {

// Accepted values of one quantity, in SI: [min, max], or (min, max] when min_exclusive.
// Non-finite values are never accepted.
struct ValueRange {
  Quantity quantity;
  double min;
  double max;
  bool min_exclusive{false};
  std::string_view unit{};  // shown after numbers in messages; default the SI unit
};

namespace value_range {

// validate, plot, test specs: the virtual hand, the sensor noise, the free start
inline constexpr ValueRange hand_stiffness{Quantity::stiffness_N_per_m, 0.0, 1e6, true};
inline constexpr ValueRange hand_damping{Quantity::damping_N_s_per_m, 0.0, 1e4};
inline constexpr ValueRange hand_mass{Quantity::mass_kg, 0.0, 10.0};
inline constexpr ValueRange noise{Quantity::dimensionless, 0.0, 1000.0, false, "counts"};
inline constexpr ValueRange free_start{Quantity::length_m, -1.0, 1.0};

// probe and test specs' "forces": the position and velocity of a point
inline constexpr ValueRange probe_position{Quantity::length_m, -1000.0, 1000.0};
inline constexpr ValueRange probe_velocity{Quantity::velocity_m_per_s, -1000.0, 1000.0};

}  // namespace value_range

// The range as messages show it: "[0, 1000] counts", "(0, 1000000] N/m".
std::string describe_range(const ValueRange& range);

// Empty when `value` is in `range`, else "must be in [0, 1000] counts, got -3 counts".
std::string range_problem(const ValueRange& range, double value);

}  // namespace hapscene
