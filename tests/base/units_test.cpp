#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "engine/base/units.hpp"

using namespace hapscene;

TEST_CASE("units: strings with units convert to SI") {
  struct Case {
    const char* text;
    Quantity quantity;
    double value_si;
  };
  const Case cases[] = {
      {"10 mm", Quantity::length_m, 0.01},          {"0.5 cm", Quantity::length_m, 0.005},
      {"-3mm", Quantity::length_m, -0.003},         {"+2 m", Quantity::length_m, 2.0},
      {"800 N/m", Quantity::stiffness_N_per_m, 800}, {"0.8 N/mm", Quantity::stiffness_N_per_m, 800},
      {"1 kN/m", Quantity::stiffness_N_per_m, 1000}, {"2 N*s/m", Quantity::damping_N_s_per_m, 2},
      {"2 N s/m", Quantity::damping_N_s_per_m, 2},   {"2 N\xC2\xB7s/m", Quantity::damping_N_s_per_m, 2},
      {"2 kHz", Quantity::frequency_Hz, 2000},       {"500 ms", Quantity::time_s, 0.5},
      {"40 g", Quantity::mass_kg, 0.04},             {"4 N/ms", Quantity::force_rate_N_per_s, 4000},
      {"1e-3 m", Quantity::length_m, 1e-3},          {"250 mN", Quantity::force_N, 0.25},
      {"50 mm/s", Quantity::velocity_m_per_s, 0.05},
  };
  for (const Case& c : cases) {
    CAPTURE(c.text);
    const QuantityParse parsed = parse_quantity(c.text);
    REQUIRE(parsed.ok);
    CHECK(parsed.quantity == c.quantity);
    CHECK(parsed.value_si == doctest::Approx(c.value_si).epsilon(1e-15));
  }
}

TEST_CASE("units: a bare number is SI of the expected quantity") {
  const QuantityParse parsed = parse_quantity_as("0.02", Quantity::length_m);
  REQUIRE(parsed.ok);
  CHECK(parsed.value_si == 0.02);
  CHECK(parsed.quantity == Quantity::length_m);
}

TEST_CASE("units: a unit of the wrong kind is an error") {
  const QuantityParse parsed = parse_quantity_as("10 mm", Quantity::stiffness_N_per_m);
  CHECK_FALSE(parsed.ok);
  CHECK(parsed.error == "expected a stiffness (N/m), got a length (\"10 mm\")");
}

TEST_CASE("units: unknown units suggest the nearest known one") {
  CHECK(parse_quantity("10 mmm").error == "unknown unit \"mmm\" (did you mean \"mm\"?)");
  CHECK(parse_quantity("3 furlongs").error == "unknown unit \"furlongs\"");
  CHECK(parse_quantity("800 N/mn").error == "unknown unit \"N/mn\" (did you mean \"N/m\"?)");
}

TEST_CASE("units: malformed and non-finite values are errors") {
  CHECK(parse_quantity("mm").error ==
        "expected a number with an optional unit, such as \"10 mm\", got \"mm\"");
  CHECK(parse_quantity("").error ==
        "expected a number with an optional unit, such as \"10 mm\", got \"\"");
  CHECK(parse_quantity("inf mm").error == "value must be finite, got \"inf mm\"");
  CHECK(parse_quantity("nan").error == "value must be finite, got \"nan\"");
  CHECK(parse_quantity("1e308 kN/m").error == "value out of range, got \"1e308 kN/m\"");
}

TEST_CASE("units: nearest_name suggests only close names") {
  const std::vector<std::string> names{"stiffness", "center", "position"};
  CHECK(nearest_name("stifness", names) == "stiffness");
  CHECK(nearest_name("centre", names) == "center");
  CHECK(nearest_name("zzzzzz", names).empty());
}
