#include "engine/harness/report.hpp"

#include <cmath>

#include "engine/base/format.hpp"

namespace hapscene {
namespace {

std::string padded(std::string text, std::size_t width) {
  if (text.size() < width) text.append(width - text.size(), ' ');
  return text;
}

// Counts of a report's checks: all, failed (with their names) and not judged.
struct Tally {
  int total{};
  int failed{};
  int not_judged{};
  std::string failures;
  void add(const std::string& where, const CheckResult& c) {
    ++total;
    if (!c.judged) ++not_judged;
    if (!c.pass) {
      ++failed;
      failures += (failures.empty() ? "" : ", ") + where + "/" + c.name;
    }
  }
};

Tally tally(const ValidationReport& report) {
  Tally t;
  for (const CheckResult& c : report.scene_checks) t.add("scene", c);
  for (const ScenarioResult& s : report.scenarios) {
    for (const CheckResult& c : s.checks) t.add(s.scenario.name, c);
  }
  return t;
}

// "60 checks", "60 checks, 2 not judged".
std::string counted(const Tally& t) {
  std::string text = printf_string("%d checks", t.total);
  if (t.not_judged > 0) text += printf_string(", %d not judged", t.not_judged);
  return text;
}

// "1 of 9 checks failed: press/passivity", then "; 2 not judged" when some were not.
std::string failed_text(const Tally& t) {
  std::string text = printf_string("%d of %d checks failed: %s", t.failed, t.total, t.failures.c_str());
  if (t.not_judged > 0) text += printf_string("; %d not judged", t.not_judged);
  return text;
}

}  // namespace

std::string format_check_row(const CheckResult& c) {
  const char* relation = c.name == "slew" ? "< " : "<= ";
  const std::string verdict = verdict_text(c);
  return padded("", 10) + padded(c.name, 15) + padded(format_value(c.value, c.unit), 16) +
         padded(relation + format_value(c.threshold, c.unit), 17) + padded(verdict, 9) +
         (verdict.size() >= 9 ? " " : "") + c.detail + "\n";
}

std::string format_report_line(const ValidationReport& report) {
  const Tally t = tally(report);
  std::string line = printf_string("%s %s (%s): ", t.failed == 0 ? "PASS" : "FAIL", report.scene_name.c_str(),
                                   report.source_path.c_str());
  if (t.failed == 0) return line + counted(t) + "\n";
  return line + failed_text(t) + "\n";
}

std::string format_value(double value, const std::string& unit) {
  if (!std::isfinite(value)) return value > 0 ? "inf" : "nan";
  if (unit == "N") return printf_string("%.3f N", value);
  if (unit == "m") return printf_string("%.3f mm", value * 1e3);
  if (unit == "s") return printf_string("%.2f us", value * 1e6);
  if (unit == "N/s") return printf_string("%.3f N/ms", value * 1e-3);
  if (unit == "ticks" || unit == "faults" || unit == "crossings") return printf_string("%.0f %s", value, unit.c_str());
  return printf_string("%.3f", value);
}

std::string format_report_table(const ValidationReport& report) {
  std::string out = printf_string(
      "validate %s (%s): %g Hz, passivity bound %s = %.0f N/m, stiffest region %.0f N/m\n",
      report.scene_name.c_str(), report.source_path.c_str(), report.rate_hz, report.passivity_bound_name,
      report.passivity_bound_N_per_m, report.stiffest_region_N_per_m);
  const HarnessOptions& o = report.options;
  out += printf_string("hand %g N/m, %g N*s/m, %g g; sensor noise %s, seed %llu\n\n",
                       o.hand_stiffness_N_per_m, o.hand_damping_N_s_per_m, o.hand_mass_kg * 1e3,
                       o.noise_counts < 0 ? "from the profile" : printf_string("%g counts", o.noise_counts).c_str(),
                       static_cast<unsigned long long>(o.seed));
  if (!report.field.behaviour.static_field()) {
    out += "force field: " + report.field.behaviour.note + "; no walls inferred from it\n\n";
  }
  out += "scenario  check          value           threshold        verdict  detail\n";

  if (!report.scene_checks.empty()) {
    out += padded("scene", 10) + "the environment as loaded and probed open loop\n";
    for (const CheckResult& c : report.scene_checks) out += format_check_row(c);
  }
  for (const ScenarioResult& s : report.scenarios) {
    out += padded(s.scenario.name, 10) + s.scenario.description + "\n";
    if (!s.scenario.applicable) {
      out += padded("", 10) + "(not applicable)\n";
      continue;
    }
    for (const CheckResult& c : s.checks) out += format_check_row(c);
  }
  const Tally t = tally(report);
  if (t.failed == 0) {
    out += "\nresult: pass (" + counted(t) + ")\n";
  } else {
    out += "\nresult: FAIL (" + failed_text(t) + ")\n";
  }
  return out;
}

std::string report_table_header(const std::string& table) {
  const std::size_t rows = table.find("scenario  check ");
  return rows == std::string::npos ? table : table.substr(0, rows);
}

std::string format_report_summary(const std::string& header, const std::vector<ReportSection>& sections) {
  std::string out = header;
  Tally all;
  for (const ReportSection& section : sections) {
    if (!section.applicable) {
      out += padded(section.name, 10) + padded("-", 6) + padded("not applicable", 26) + section.description + "\n";
      continue;
    }
    Tally t;
    for (const CheckResult& c : section.checks) {
      t.add(section.name, c);
      all.add(section.name, c);
    }
    const std::string counts = t.failed > 0 ? printf_string("%d of %d checks failed", t.failed, t.total)
                                            : counted(t);
    out += padded(section.name, 10) + padded(t.failed > 0 ? "FAIL" : "pass", 6) + padded(counts, 26) +
           section.description + "\n";
    for (const CheckResult& c : section.checks) {
      if (!c.pass) out += format_check_row(c);
    }
  }
  out += all.failed == 0 ? "\nresult: pass (" + counted(all) + ")\n" : "\nresult: FAIL (" + failed_text(all) + ")\n";
  return out;
}

std::string format_report_summary(const ValidationReport& report) {
  std::vector<ReportSection> sections;
  if (!report.scene_checks.empty()) {
    sections.push_back({"scene", "the environment as loaded and probed open loop", true, report.scene_checks});
  }
  for (const ScenarioResult& s : report.scenarios) {
    sections.push_back({s.scenario.name, s.scenario.description, s.scenario.applicable, s.checks});
  }
  return format_report_summary(report_table_header(format_report_table(report)), sections);
}

nlohmann::json check_to_json(const CheckResult& c) {
  return {{"name", c.name}, {"value", c.value}, {"threshold", c.threshold}, {"unit", c.unit},
          {"pass", c.pass}, {"verdict", c.judged ? (c.pass ? "pass" : "fail") : "not judged"},
          {"detail", c.detail}};
}

nlohmann::json report_to_json(const ValidationReport& report) {
  using nlohmann::json;
  json regions = json::array();
  for (const StiffRegion& r : report.field.regions) {
    regions.push_back({{"low_m", r.low_m}, {"high_m", r.high_m}, {"low_is_edge", r.low_is_edge},
                       {"high_is_edge", r.high_is_edge}, {"stiffness_N_per_m", r.stiffness_N_per_m}});
  }
  const HarnessOptions& o = report.options;
  json out = {
      {"schema", kReportSchema},
      {"scene", {{"name", report.scene_name}, {"source", report.source_path}, {"rate_hz", report.rate_hz},
                 {"passivity_bound_N_per_m", report.passivity_bound_N_per_m},
                 {"passivity_bound", report.passivity_bound_name},
                 {"stiffest_region_N_per_m", report.stiffest_region_N_per_m},
                 {"stiff_regions", regions},
                 {"static_field", report.field.behaviour.static_field()},
                 {"field_note", report.field.behaviour.note},
                 {"field_script_faults", report.field.faults.lines()},
                 {"load_warnings", nlohmann::json::array()}}},
      {"options", {{"hand_stiffness_N_per_m", o.hand_stiffness_N_per_m},
                   {"hand_damping_N_s_per_m", o.hand_damping_N_s_per_m},
                   {"hand_mass_kg", o.hand_mass_kg},
                   {"noise_counts", o.noise_counts < 0 ? json(nullptr) : json(o.noise_counts)},
                   {"seed", o.seed},
                   {"free_start_m", o.free_start_m}}},
      {"pass", report.pass},
      {"scene_checks", json::array()},
      {"scenarios", json::array()}};
  for (const std::string& w : report.load_warnings) out["scene"]["load_warnings"].push_back(w);
  for (const CheckResult& c : report.scene_checks) out["scene_checks"].push_back(check_to_json(c));

  for (const ScenarioResult& s : report.scenarios) {
    const ScenarioMetrics& m = s.metrics;
    json scenario = {{"name", s.scenario.name}, {"description", s.scenario.description},
                     {"applicable", s.scenario.applicable}, {"duration_s", s.scenario.duration_s},
                     {"pass", s.pass}};
    if (s.scenario.applicable) {
      json script_faults = json::array();
      for (const auto& f : m.script_faults) script_faults.push_back({{"message", f.message}, {"where", f.where}});
      json metrics = {
          {"ticks", m.ticks},
          {"max_requested_N", m.max_requested_N},
          {"max_output_N", m.max_output_N},
          {"max_output_x_m", m.max_output_x_m},
          {"max_output_t_s", m.max_output_t_s},
          {"time_at_limit_s", m.time_at_limit_s},
          {"time_at_limit_fraction", m.time_at_limit_fraction},
          {"max_slew_N_per_s", m.max_slew_N_per_s},
          {"force_jitter_N", m.force_jitter_N},
          {"slip_force_ticks", m.slip_force_ticks},
          {"slip_step_ticks", m.slip_step_ticks},
          {"max_step_1ms_N", m.max_step_1ms_N},
          {"slip_first_x_m", m.slip_first_t_s < 0.0 ? json(nullptr) : json(m.slip_first_x_m)},
          {"slip_first_t_s", m.slip_first_t_s < 0.0 ? json(nullptr) : json(m.slip_first_t_s)},
          {"jitter_peak_N", m.jitter_peak_N},
          {"jitter_peak_x_m", m.jitter_peak_x_m},
          {"jitter_peak_t_s", m.jitter_peak_t_s},
          {"passivity", {{"motor_work_J", m.passivity.motor_work_J}, {"stored_J", m.passivity.stored_J},
                         {"created_J", m.passivity.created_J}, {"dissipated_J", m.passivity.dissipated_J},
                         {"net_J", m.passivity.net_J}, {"ratio", m.passivity.ratio},
                         {"grows", m.passivity.grows}}},
          {"oscillation", nullptr},
          {"max_penetration_m", m.max_penetration_m},
          {"max_penetration_x_m", m.max_penetration_x_m},
          {"script_errors", m.script_errors},
          {"script_budget_overruns", m.script_budget_overruns},
          {"script_faults", script_faults},
          {"tick_compute_s", {{"p50", m.compute_p50_s}, {"p99", m.compute_p99_s}, {"max", m.compute_max_s}}},
          {"safety", {{"nonfinite_faults", m.safety.nonfinite_faults},
                      {"outside_workspace_ticks", m.safety.outside_workspace_ticks},
                      {"soft_start_ticks", m.safety.soft_start_ticks},
                      {"clamped_ticks", m.safety.clamped_ticks},
                      {"slew_limited_ticks", m.safety.slew_limited_ticks}}}};
      if (m.oscillation) {
        const OscillationMetrics& w = *m.oscillation;
        metrics["oscillation"] = {{"from_s", w.from_s}, {"half_cycles", w.half_cycles},
                                  {"frequency_Hz", w.frequency_Hz},
                                  {"initial_amplitude_m", w.initial_amplitude_m},
                                  {"residual_amplitude_m", w.residual_amplitude_m},
                                  {"growth", w.growth}, {"rest_m", w.rest_m}};
      }
      scenario["metrics"] = metrics;
      json checks = json::array();
      for (const CheckResult& c : s.checks) {
        checks.push_back(check_to_json(c));
      }
      scenario["checks"] = checks;
    }
    out["scenarios"].push_back(scenario);
  }
  return out;
}

}  // namespace hapscene
