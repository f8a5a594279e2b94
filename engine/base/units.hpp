#pragma once
// Physical quantities in environment files: a plain number is SI, a string such as
// "10 mm", "800 N/m" or "2 kHz" is converted to SI. Each field expects one quantity;
// a unit of another quantity is an error.
#include <string>
#include <string_view>

namespace hapscene {

enum class Quantity {
  dimensionless,
  length_m,
  velocity_m_per_s,
  force_N,
  stiffness_N_per_m,
  damping_N_s_per_m,
  time_s,
  frequency_Hz,
  mass_kg,
  force_rate_N_per_s,
  // Joint-space quantities of multi-axis device profiles.
  angle_rad,
  torque_N_m,
  inertia_kg_m2,
  rotational_damping_N_m_s_per_rad,
  rotational_stiffness_N_m_per_rad,
};

// The SI unit written in messages, e.g. "N/m".
std::string_view si_unit(Quantity quantity);
// A readable name for messages, e.g. "stiffness".
std::string_view quantity_name(Quantity quantity);

// Result of reading a "<number> <unit>" string.
struct QuantityParse {
  bool ok{};
  double value_si{};
  Quantity quantity{Quantity::dimensionless};
  std::string error;  // set when !ok: what is wrong, without the location
};

// Reads "10 mm", "-0.5cm", "2 N*s/m", "2 kHz", "1e-3 m", "3" (dimensionless).
// The value must be finite. Unknown units get an error suggesting the nearest known one.
QuantityParse parse_quantity(std::string_view text);

// Reads `text` as a value of `expected`. A bare number string ("3") is taken as SI.
// On a unit of another quantity, error reads e.g. "expected a stiffness (N/m), got a length ("10 mm")".
QuantityParse parse_quantity_as(std::string_view text, Quantity expected);

// Names longer than this are never suggested.
inline constexpr std::size_t kMaxSuggestedNameBytes = 48;

// Levenshtein distance, for "did you mean" suggestions; the largest size_t when either
// name is longer than kMaxSuggestedNameBytes. Allocates nothing.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate closest to `word`, or empty when none is reasonably close.
template <typename Range>
std::string nearest_name(std::string_view word, const Range& candidates) {
  std::string best;
  std::size_t best_distance = word.size() / 2 + 2;
  for (const auto& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(candidate);
    }
  }
  return best;
}

}  // namespace hapscene
