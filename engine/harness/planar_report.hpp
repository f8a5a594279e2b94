#pragma once
// Reports of a 2-DOF validate run, overloads of report.hpp's and figures.hpp's: the
// terminal table, the --quiet line and the JSON report (schema "hapscene-validate/2", with
// "axes": 2 and the fields 2-D adds; docs/reference/validate-report.md, "In 2-D"), and the
// figure (--plot).
#include <string>

#include <nlohmann/json.hpp>

#include "engine/harness/planar_validate.hpp"

namespace hapscene {

std::string format_report_table(const PlanarValidationReport& report);
std::string format_report_line(const PlanarValidationReport& report);
// `validate` by default: the table's header, a line per scenario, the failed checks'
// rows (format_report_summary in report.hpp).
std::string format_report_summary(const PlanarValidationReport& report);
nlohmann::json report_to_json(const PlanarValidationReport& report);

// The figure of a 2-D validate run: the force field with the shapes and the workspace,
// and the first failing scenario's (else the first applicable one's) handle and proxy
// paths and time series (engine/harness/planar_figure.hpp).
std::string validation_figure_svg(const PlanarScene& scene, const PlanarValidationReport& report);

}  // namespace hapscene
