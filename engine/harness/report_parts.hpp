#pragma once
// What the 1-D and the 2-D validate reports (report.cpp, planar_report.cpp) write alike:
// the table's hand line and check rows, the --quiet line, and the JSON of the options, of
// a scenario and of the metrics both dimensions measure (a position is a number in 1-D,
// [x, y] in 2-D). Internal to the harness.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/axes.hpp"
#include "engine/harness/report.hpp"

namespace hapscene {

// The report's sections: "scene" (described as `scene_description`) when it has checks,
// then a section per scenario, for a report of either dimension.
template <class Report>
std::vector<ReportSection> report_sections(const Report& report, const std::string& scene_description) {
  std::vector<ReportSection> sections;
  if (!report.scene_checks.empty()) sections.push_back({"scene", scene_description, true, report.scene_checks});
  for (const auto& s : report.scenarios) {
    sections.push_back({s.scenario.name, s.scenario.description, s.scenario.applicable, s.checks});
  }
  return sections;
}

// "hand 200 N/m, 2 N*s/m, 20 g; sensor noise from the profile, seed 1" and a blank line.
std::string format_hand_line(const HarnessOptions& options);

// The table below its header: the column titles, each section with its check rows (or
// "(not applicable)") and the result line.
std::string format_report_rows(const std::vector<ReportSection>& sections);

// The --quiet line of a report with these sections.
std::string format_report_line(const std::string& scene_name, const std::string& source_path,
                               const std::vector<ReportSection>& sections);

// A position in the JSON report: a number in 1-D, [x, y] in 2-D.
inline nlohmann::json position_json(double x_m) { return x_m; }
inline nlohmann::json position_json(const Vec2& x_m) { return nlohmann::json::array({x_m[0], x_m[1]}); }

// "options" without "free_start_m" (whose form depends on the dimension).
nlohmann::json options_json(const HarnessOptions& options);

// The oscillation's numbers; "rest_m" is the 1-D rest position (2-D sets its own).
nlohmann::json oscillation_json(const OscillationMetrics& oscillation);

// The metrics 1-D and 2-D measure alike (ScenarioMetrics, PlanarScenarioMetrics); each
// report adds its own. "oscillation" is null here.
template <class Metrics>
nlohmann::json shared_metrics_json(const Metrics& m) {
  using nlohmann::json;
  json script_faults = json::array();
  for (const auto& f : m.script_faults) script_faults.push_back({{"message", f.message}, {"where", f.where}});
  return {{"ticks", m.ticks},
          {"max_requested_N", m.max_requested_N},
          {"max_output_N", m.max_output_N},
          {"max_output_x_m", position_json(m.max_output_x_m)},
          {"max_output_t_s", m.max_output_t_s},
          {"time_at_limit_s", m.time_at_limit_s},
          {"time_at_limit_fraction", m.time_at_limit_fraction},
          {"max_slew_N_per_s", m.max_slew_N_per_s},
          {"force_jitter_N", m.force_jitter_N},
          {"jitter_peak_N", m.jitter_peak_N},
          {"jitter_peak_x_m", position_json(m.jitter_peak_x_m)},
          {"jitter_peak_t_s", m.jitter_peak_t_s},
          {"passivity", {{"motor_work_J", m.passivity.motor_work_J}, {"stored_J", m.passivity.stored_J},
                         {"created_J", m.passivity.created_J}, {"dissipated_J", m.passivity.dissipated_J},
                         {"net_J", m.passivity.net_J}, {"ratio", m.passivity.ratio}, {"grows", m.passivity.grows}}},
          {"oscillation", nullptr},
          {"max_penetration_m", m.max_penetration_m},
          {"max_penetration_x_m", position_json(m.max_penetration_x_m)},
          {"script_errors", m.script_errors},
          {"script_budget_overruns", m.script_budget_overruns},
          {"script_faults", script_faults},
          {"tick_compute_s", {{"p50", m.compute_p50_s}, {"p99", m.compute_p99_s}, {"max", m.compute_max_s}}},
          {"safety", {{"nonfinite_faults", m.safety.nonfinite_faults},
                      {"outside_workspace_ticks", m.safety.outside_workspace_ticks},
                      {"soft_start_ticks", m.safety.soft_start_ticks},
                      {"clamped_ticks", m.safety.clamped_ticks},
                      {"slew_limited_ticks", m.safety.slew_limited_ticks}}}};
}

// The JSON report's frame: "schema", "scene" (`scene`, with the report's load_warnings),
// "options", "pass", "scene_checks", and "scenarios" (empty, for the caller to fill).
template <class Report>
nlohmann::json report_json_frame(const Report& report, nlohmann::json scene, nlohmann::json options) {
  scene["load_warnings"] = report.load_warnings;
  nlohmann::json out = {{"schema", kReportSchema},
                        {"scene", std::move(scene)},
                        {"options", std::move(options)},
                        {"pass", report.pass},
                        {"scene_checks", nlohmann::json::array()},
                        {"scenarios", nlohmann::json::array()}};
  for (const CheckResult& c : report.scene_checks) out["scene_checks"].push_back(check_to_json(c));
  return out;
}

// A scenario's entry, the same keys for every scenario: name, description, applicable,
// duration_s, pass, `metrics` (null for one that does not apply: it did not run) and its
// checks (none then).
template <class ScenarioResult>
nlohmann::json scenario_json(const ScenarioResult& s, const nlohmann::json& metrics) {
  nlohmann::json checks = nlohmann::json::array();
  for (const CheckResult& c : s.checks) checks.push_back(check_to_json(c));
  return {{"name", s.scenario.name},
          {"description", s.scenario.description},
          {"applicable", s.scenario.applicable},
          {"duration_s", s.scenario.duration_s},
          {"pass", s.pass},
          {"metrics", s.scenario.applicable ? metrics : nlohmann::json(nullptr)},
          {"checks", s.scenario.applicable ? checks : nlohmann::json::array()}};
}

}  // namespace hapscene
