#pragma once
// Validation reports: a table for the terminal and JSON for tools (schema in README,
// "hapscene validate").
#include <string>

#include <nlohmann/json.hpp>

#include "engine/harness/validate.hpp"

namespace hapscene {

inline constexpr const char* kReportSchema = "hapscene-validate/1";

// The terminal table, one line per check, and a result line.
std::string format_report_table(const ValidationReport& report);

// The JSON report (nlohmann writes non-finite numbers as null).
nlohmann::json report_to_json(const ValidationReport& report);

// A value with its unit as the table shows it ("4.305 N", "8.571 mm", "1.63 us").
std::string format_value(double value, const std::string& unit);

}  // namespace hapscene
