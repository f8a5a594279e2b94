#pragma once
// Validation reports: a table for the terminal and JSON for tools (schema in
// docs/reference/validate-report.md).
#include <string>

#include <nlohmann/json.hpp>

#include "engine/harness/validate.hpp"

namespace hapscene {

inline constexpr const char* kReportSchema = "hapscene-validate/2";

// The terminal table, one line per check, and a result line.
std::string format_report_table(const ValidationReport& report);

// One part of a report (the scene's checks, or a scenario) as the summary shows it.
struct ReportSection {
  std::string name;
  std::string description;
  bool applicable{true};
  std::vector<CheckResult> checks;
};

// `validate` by default: `header` (the table's lines above its check rows), one line per
// section (verdict, checks counted, description), the rows of only the checks that
// failed under it, and the result line. `validate --verbose` prints the table instead.
std::string format_report_summary(const std::string& header, const std::vector<ReportSection>& sections);
std::string format_report_summary(const ValidationReport& report);

// The lines of a table above its check rows (its title, the hand and the noise).
std::string report_table_header(const std::string& table);

// `validate --quiet`: one line per file with its verdict ("PASS wall (environments/wall.json):
// 60 checks", "FAIL ...: 1 of 9 checks failed: press/passivity").
std::string format_report_line(const ValidationReport& report);

// One check as JSON ("verdict": "pass", "fail" or "not judged"; "pass" is false only
// for "fail").
nlohmann::json check_to_json(const CheckResult& check);

// The JSON report (nlohmann writes non-finite numbers as null).
nlohmann::json report_to_json(const ValidationReport& report);

// One row of the table: a check's name, value, threshold, verdict and detail.
std::string format_check_row(const CheckResult& check);

// A value with its unit as the table shows it ("4.305 N", "8.571 mm", "1.63 us").
std::string format_value(double value, const std::string& unit);

}  // namespace hapscene
