#include "engine/harness/report.hpp"

#include <cmath>

#include "engine/base/format.hpp"
#include "engine/harness/report_parts.hpp"

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

Tally tally(const std::vector<ReportSection>& sections) {
  Tally t;
  for (const ReportSection& section : sections) {
    for (const CheckResult& c : section.checks) t.add(section.name, c);
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

// "result: pass (60 checks)" or "result: FAIL (...)", after a blank line.
std::string result_line(const Tally& t) {
  return t.failed == 0 ? "\nresult: pass (" + counted(t) + ")\n" : "\nresult: FAIL (" + failed_text(t) + ")\n";
}

constexpr const char* kSceneDescription = "the environment as loaded and probed open loop";

}  // namespace

std::string format_check_row(const CheckResult& c) {
  const char* relation = c.name == "slew" ? "< " : "<= ";
  const std::string verdict = verdict_text(c);
  return padded("", 10) + padded(c.name, 15) + padded(format_value(c.value, c.unit), 16) +
         padded(relation + format_value(c.threshold, c.unit), 17) + padded(verdict, 9) +
         (verdict.size() >= 9 ? " " : "") + c.detail + "\n";
}

std::string format_report_line(const std::string& scene_name, const std::string& source_path,
                               const std::vector<ReportSection>& sections) {
  const Tally t = tally(sections);
  std::string line =
      printf_string("%s %s (%s): ", t.failed == 0 ? "PASS" : "FAIL", scene_name.c_str(), source_path.c_str());
  return line + (t.failed == 0 ? counted(t) : failed_text(t)) + "\n";
}

std::string format_report_line(const ValidationReport& report) {
  return format_report_line(report.scene_name, report.source_path, report_sections(report, kSceneDescription));
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

std::string format_hand_line(const HarnessOptions& o) {
  return printf_string("hand %g N/m, %g N*s/m, %g g; sensor noise %s, seed %llu\n\n", o.hand_stiffness_N_per_m,
                       o.hand_damping_N_s_per_m, o.hand_mass_kg * 1e3,
                       o.noise_counts < 0 ? "from the profile" : printf_string("%g counts", o.noise_counts).c_str(),
                       static_cast<unsigned long long>(o.seed));
}

std::string format_report_rows(const std::vector<ReportSection>& sections) {
  std::string out = "scenario  check          value           threshold        verdict  detail\n";
  for (const ReportSection& section : sections) {
    out += padded(section.name, 10) + section.description + "\n";
    if (!section.applicable) {
      out += padded("", 10) + "(not applicable)\n";
      continue;
    }
    for (const CheckResult& c : section.checks) out += format_check_row(c);
  }
  return out + result_line(tally(sections));
}

std::string format_report_table(const ValidationReport& report) {
  std::string out = printf_string(
      "validate %s (%s): %g Hz, passivity bound %s = %.0f N/m, stiffest region %.0f N/m\n",
      report.scene_name.c_str(), report.source_path.c_str(), report.rate_hz, report.passivity_bound_name,
      report.passivity_bound_N_per_m, report.stiffest_region_N_per_m);
  out += format_hand_line(report.options);
  if (!report.field.behaviour.static_field()) {
    out += "force field: " + report.field.behaviour.note + "; no walls inferred from it\n\n";
  }
  return out + format_report_rows(report_sections(report, kSceneDescription));
}

std::string report_table_header(const std::string& table) {
  const std::size_t rows = table.find("scenario  check ");
  return rows == std::string::npos ? table : table.substr(0, rows);
}

std::string format_report_summary(const std::string& header, const std::vector<ReportSection>& sections) {
  std::string out = header;
  for (const ReportSection& section : sections) {
    if (!section.applicable) {
      out += padded(section.name, 10) + padded("-", 6) + padded("not applicable", 26) + section.description + "\n";
      continue;
    }
    const Tally t = tally({section});
    const std::string counts = t.failed > 0 ? printf_string("%d of %d checks failed", t.failed, t.total)
                                            : counted(t);
    out += padded(section.name, 10) + padded(t.failed > 0 ? "FAIL" : "pass", 6) + padded(counts, 26) +
           section.description + "\n";
    for (const CheckResult& c : section.checks) {
      if (!c.pass) out += format_check_row(c);
    }
  }
  return out + result_line(tally(sections));
}

std::string format_report_summary(const ValidationReport& report) {
  return format_report_summary(report_table_header(format_report_table(report)),
                               report_sections(report, kSceneDescription));
}

nlohmann::json check_to_json(const CheckResult& c) {
  return {{"name", c.name}, {"value", c.value}, {"threshold", c.threshold}, {"unit", c.unit},
          {"pass", c.pass}, {"verdict", verdict_text(c)},  // the table's word
          {"detail", c.detail}};
}

nlohmann::json options_json(const HarnessOptions& o) {
  using nlohmann::json;
  return {{"hand_stiffness_N_per_m", o.hand_stiffness_N_per_m},
          {"hand_damping_N_s_per_m", o.hand_damping_N_s_per_m},
          {"hand_mass_kg", o.hand_mass_kg},
          {"noise_counts", o.noise_counts < 0 ? json(nullptr) : json(o.noise_counts)},
          {"seed", o.seed}};
}

nlohmann::json oscillation_json(const OscillationMetrics& w) {
  return {{"from_s", w.from_s}, {"half_cycles", w.half_cycles}, {"frequency_Hz", w.frequency_Hz},
          {"initial_amplitude_m", w.initial_amplitude_m}, {"residual_amplitude_m", w.residual_amplitude_m},
          {"growth", w.growth}, {"rest_m", w.rest_m}};
}

nlohmann::json report_to_json(const ValidationReport& report) {
  using nlohmann::json;
  json regions = json::array();
  for (const StiffRegion& r : report.field.regions) {
    regions.push_back({{"low_m", r.low_m}, {"high_m", r.high_m}, {"low_is_edge", r.low_is_edge},
                       {"high_is_edge", r.high_is_edge}, {"stiffness_N_per_m", r.stiffness_N_per_m}});
  }
  json options = options_json(report.options);
  options["free_start_m"] = report.options.free_start_m;
  json out = report_json_frame(
      report,
      {{"name", report.scene_name}, {"source", report.source_path}, {"rate_hz", report.rate_hz},
       {"passivity_bound_N_per_m", report.passivity_bound_N_per_m},
       {"passivity_bound", report.passivity_bound_name},
       {"stiffest_region_N_per_m", report.stiffest_region_N_per_m},
       {"stiff_regions", regions},
       {"static_field", report.field.behaviour.static_field()},
       {"field_note", report.field.behaviour.note},
       {"field_script_faults", report.field.faults.lines()}},
      options);
  for (const ScenarioResult& s : report.scenarios) {
    const ScenarioMetrics& m = s.metrics;
    json metrics = shared_metrics_json(m);
    metrics["slip_force_ticks"] = m.slip_force_ticks;
    metrics["slip_step_ticks"] = m.slip_step_ticks;
    metrics["max_step_1ms_N"] = m.max_step_1ms_N;
    metrics["slip_first_x_m"] = m.slip_first_t_s < 0.0 ? json(nullptr) : json(m.slip_first_x_m);
    metrics["slip_first_t_s"] = m.slip_first_t_s < 0.0 ? json(nullptr) : json(m.slip_first_t_s);
    if (m.oscillation) metrics["oscillation"] = oscillation_json(*m.oscillation);
    out["scenarios"].push_back(scenario_json(s, metrics));
  }
  return out;
}

}  // namespace hapscene
