#include "engine/base/units.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <vector>

namespace hapscene {
namespace {

struct UnitEntry {
  std::string_view symbol;
  Quantity quantity;
  double to_si;
};

// Every accepted spelling. Multiplication may be written "*", "·" or a space ("N s/m").
constexpr std::array kUnits{
    UnitEntry{"m", Quantity::length_m, 1.0},
    UnitEntry{"cm", Quantity::length_m, 1e-2},
    UnitEntry{"mm", Quantity::length_m, 1e-3},
    UnitEntry{"um", Quantity::length_m, 1e-6},
    UnitEntry{"µm", Quantity::length_m, 1e-6},
    UnitEntry{"m/s", Quantity::velocity_m_per_s, 1.0},
    UnitEntry{"cm/s", Quantity::velocity_m_per_s, 1e-2},
    UnitEntry{"mm/s", Quantity::velocity_m_per_s, 1e-3},
    UnitEntry{"N", Quantity::force_N, 1.0},
    UnitEntry{"mN", Quantity::force_N, 1e-3},
    UnitEntry{"N/m", Quantity::stiffness_N_per_m, 1.0},
    UnitEntry{"N/cm", Quantity::stiffness_N_per_m, 1e2},
    UnitEntry{"N/mm", Quantity::stiffness_N_per_m, 1e3},
    UnitEntry{"kN/m", Quantity::stiffness_N_per_m, 1e3},
    UnitEntry{"N*s/m", Quantity::damping_N_s_per_m, 1.0},
    UnitEntry{"Ns/m", Quantity::damping_N_s_per_m, 1.0},
    UnitEntry{"N*s/mm", Quantity::damping_N_s_per_m, 1e3},
    UnitEntry{"Ns/mm", Quantity::damping_N_s_per_m, 1e3},
    UnitEntry{"kg/s", Quantity::damping_N_s_per_m, 1.0},
    UnitEntry{"s", Quantity::time_s, 1.0},
    UnitEntry{"ms", Quantity::time_s, 1e-3},
    UnitEntry{"us", Quantity::time_s, 1e-6},
    UnitEntry{"µs", Quantity::time_s, 1e-6},
    UnitEntry{"Hz", Quantity::frequency_Hz, 1.0},
    UnitEntry{"kHz", Quantity::frequency_Hz, 1e3},
    UnitEntry{"kg", Quantity::mass_kg, 1.0},
    UnitEntry{"g", Quantity::mass_kg, 1e-3},
    UnitEntry{"N/s", Quantity::force_rate_N_per_s, 1.0},
    UnitEntry{"N/ms", Quantity::force_rate_N_per_s, 1e3},
    UnitEntry{"rad", Quantity::angle_rad, 1.0},
    UnitEntry{"mrad", Quantity::angle_rad, 1e-3},
    UnitEntry{"deg", Quantity::angle_rad, 0.017453292519943295},
    UnitEntry{"N*m", Quantity::torque_N_m, 1.0},
    UnitEntry{"Nm", Quantity::torque_N_m, 1.0},
    UnitEntry{"mN*m", Quantity::torque_N_m, 1e-3},
    UnitEntry{"mNm", Quantity::torque_N_m, 1e-3},
    UnitEntry{"kg*m^2", Quantity::inertia_kg_m2, 1.0},
    UnitEntry{"g*cm^2", Quantity::inertia_kg_m2, 1e-7},
    UnitEntry{"kg*mm^2", Quantity::inertia_kg_m2, 1e-6},
    UnitEntry{"N*m*s/rad", Quantity::rotational_damping_N_m_s_per_rad, 1.0},
    UnitEntry{"mN*m*s/rad", Quantity::rotational_damping_N_m_s_per_rad, 1e-3},
    UnitEntry{"N*m/rad", Quantity::rotational_stiffness_N_m_per_rad, 1.0},
    UnitEntry{"mN*m/rad", Quantity::rotational_stiffness_N_m_per_rad, 1e-3},
};

// Removes spaces and writes "·" as "*", so "N s/m", "N·s/m" and "N*s/m" compare equal.
std::string normalise_unit(std::string_view unit) {
  std::string out;
  std::string_view rest = unit;
  while (!rest.empty()) {
    if (rest.substr(0, 2) == "\xC2\xB7") {  // U+00B7 middle dot
      out += '*';
      rest.remove_prefix(2);
      continue;
    }
    const char c = rest.front();
    rest.remove_prefix(1);
    if (c == ' ' || c == '\t') {
      // "N s/m": a space between two unit letters means multiplication.
      if (!out.empty() && out.back() != '*' && out.back() != '/' && !rest.empty() &&
          rest.front() != ' ' && rest.front() != '/' && rest.front() != '*') {
        out += '*';
      }
      continue;
    }
    out += c;
  }
  return out;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

// "a length", "an angle".
std::string with_article(std::string_view name) {
  const bool vowel = !name.empty() && std::string_view("aeiou").find(name.front()) != std::string_view::npos;
  return (vowel ? "an " : "a ") + std::string(name);
}

}  // namespace

std::string_view si_unit(Quantity quantity) {
  switch (quantity) {
    case Quantity::dimensionless: return "";
    case Quantity::length_m: return "m";
    case Quantity::velocity_m_per_s: return "m/s";
    case Quantity::force_N: return "N";
    case Quantity::stiffness_N_per_m: return "N/m";
    case Quantity::damping_N_s_per_m: return "N*s/m";
    case Quantity::time_s: return "s";
    case Quantity::frequency_Hz: return "Hz";
    case Quantity::mass_kg: return "kg";
    case Quantity::force_rate_N_per_s: return "N/s";
    case Quantity::angle_rad: return "rad";
    case Quantity::torque_N_m: return "N*m";
    case Quantity::inertia_kg_m2: return "kg*m^2";
    case Quantity::rotational_damping_N_m_s_per_rad: return "N*m*s/rad";
    case Quantity::rotational_stiffness_N_m_per_rad: return "N*m/rad";
  }
  return "";
}

std::string_view quantity_name(Quantity quantity) {
  switch (quantity) {
    case Quantity::dimensionless: return "plain number";
    case Quantity::length_m: return "length";
    case Quantity::velocity_m_per_s: return "velocity";
    case Quantity::force_N: return "force";
    case Quantity::stiffness_N_per_m: return "stiffness";
    case Quantity::damping_N_s_per_m: return "damping";
    case Quantity::time_s: return "time";
    case Quantity::frequency_Hz: return "frequency";
    case Quantity::mass_kg: return "mass";
    case Quantity::force_rate_N_per_s: return "force rate";
    case Quantity::angle_rad: return "angle";
    case Quantity::torque_N_m: return "torque";
    case Quantity::inertia_kg_m2: return "moment of inertia";
    case Quantity::rotational_damping_N_m_s_per_rad: return "rotational damping";
    case Quantity::rotational_stiffness_N_m_per_rad: return "rotational stiffness";
  }
  return "";
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // One row on the stack: no allocation, so script error paths inside the tick may use it.
  if (a.size() > kMaxSuggestedNameBytes || b.size() > kMaxSuggestedNameBytes) {
    return static_cast<std::size_t>(-1);
  }
  std::size_t row[kMaxSuggestedNameBytes + 1];
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({above + 1, row[j - 1] + 1, substitute});
      diagonal = above;
    }
  }
  return row[b.size()];
}

QuantityParse parse_quantity(std::string_view text) {
  QuantityParse result;
  const std::string_view trimmed = trim(text);

  // The number: std::from_chars accepts no leading '+', so skip one.
  std::string_view number_text = trimmed;
  if (!number_text.empty() && number_text.front() == '+') number_text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] =
      std::from_chars(number_text.data(), number_text.data() + number_text.size(), value);
  // A number past what a double holds ("1e400", "1e-400") is out of range, not malformed.
  if (ec == std::errc::result_out_of_range) {
    result.error = "value out of range, got \"" + std::string(text) + "\"";
    return result;
  }
  if (ec != std::errc() || end == number_text.data()) {
    result.error = "expected a number with an optional unit, such as \"10 mm\", got \"" +
                   std::string(text) + "\"";
    return result;
  }
  if (!std::isfinite(value)) {
    result.error = "value must be finite, got \"" + std::string(text) + "\"";
    return result;
  }

  // The unit: the rest of the text.
  const std::string_view unit_text =
      trim(number_text.substr(static_cast<std::size_t>(end - number_text.data())));
  if (unit_text.empty()) {
    result.ok = true;
    result.value_si = value;
    result.quantity = Quantity::dimensionless;
    return result;
  }
  const std::string unit = normalise_unit(unit_text);
  for (const UnitEntry& entry : kUnits) {
    if (entry.symbol == unit) {
      const double si = value * entry.to_si;
      if (!std::isfinite(si)) {
        result.error = "value out of range, got \"" + std::string(text) + "\"";
        return result;
      }
      result.ok = true;
      result.value_si = si;
      result.quantity = entry.quantity;
      return result;
    }
  }
  std::vector<std::string_view> symbols;
  for (const UnitEntry& entry : kUnits) symbols.push_back(entry.symbol);
  result.error = "unknown unit \"" + std::string(unit_text) + "\"";
  const std::string suggestion = nearest_name(unit, symbols);
  if (!suggestion.empty()) result.error += " (did you mean \"" + suggestion + "\"?)";
  return result;
}

QuantityParse parse_quantity_as(std::string_view text, Quantity expected) {
  QuantityParse result = parse_quantity(text);
  if (!result.ok) return result;
  if (result.quantity == Quantity::dimensionless) {
    result.quantity = expected;  // a bare number is SI
    return result;
  }
  if (result.quantity != expected) {
    QuantityParse wrong;
    wrong.error = "expected " + with_article(quantity_name(expected));
    if (expected != Quantity::dimensionless) wrong.error += " (" + std::string(si_unit(expected)) + ")";
    wrong.error += ", got " + with_article(quantity_name(result.quantity)) + " (\"" +
                   std::string(text) + "\")";
    return wrong;
  }
  return result;
}

}  // namespace hapscene
