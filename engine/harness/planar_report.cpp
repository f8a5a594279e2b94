#include "engine/harness/planar_report.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/format.hpp"
#include "engine/harness/planar_figure.hpp"
#include "engine/harness/report.hpp"

namespace hapscene {
namespace {

using nlohmann::json;

json vec(const Vec2& v) { return json::array({v[0], v[1]}); }

std::string padded(std::string text, std::size_t width) {
  if (text.size() < width) text.append(width - text.size(), ' ');
  return text;
}

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

Tally tally(const PlanarValidationReport& report) {
  Tally t;
  for (const CheckResult& c : report.scene_checks) t.add("scene", c);
  for (const PlanarScenarioResult& s : report.scenarios) {
    for (const CheckResult& c : s.checks) t.add(s.scenario.name, c);
  }
  return t;
}

std::string counted(const Tally& t) {
  std::string text = printf_string("%d checks", t.total);
  if (t.not_judged > 0) text += printf_string(", %d not judged", t.not_judged);
  return text;
}

std::string failed_text(const Tally& t) {
  std::string text = printf_string("%d of %d checks failed: %s", t.failed, t.total, t.failures.c_str());
  if (t.not_judged > 0) text += printf_string("; %d not judged", t.not_judged);
  return text;
}

std::string pose_text(const PlanarPoseBound& pose) {
  return printf_string("%.3g N/m (%s) at (%.1f, %.1f) mm", pose.bound_N_per_m, pose.name, pose.x_m[0] * 1e3,
                       pose.x_m[1] * 1e3);
}

json pose_json(const PlanarPoseBound& pose) {
  return {{"x_m", vec(pose.x_m)}, {"viscous_N_per_m", pose.viscous_N_per_m},
          {"coulomb_N_per_m", pose.coulomb_N_per_m}, {"bound_N_per_m", pose.bound_N_per_m},
          {"bound", pose.name}, {"condition", pose.condition}};
}

}  // namespace

std::string format_planar_report_line(const PlanarValidationReport& report) {
  const Tally t = tally(report);
  std::string line = printf_string("%s %s (%s): ", t.failed == 0 ? "PASS" : "FAIL", report.scene_name.c_str(),
                                   report.source_path.c_str());
  return line + (t.failed == 0 ? counted(t) : failed_text(t)) + "\n";
}

std::string format_planar_report_table(const PlanarValidationReport& report) {
  const PlanarStiffnessBound& b = report.bound;
  std::string out = printf_string("validate %s (%s): 2 axes, %g Hz, stiffest shape or spring %.0f N/m%s\n",
                                  report.scene_name.c_str(), report.source_path.c_str(), report.rate_hz,
                                  b.stiffest_N_per_m,
                                  report.scripts == 0 ? ""
                                  : report.scripts == 1
                                      ? " (not counting the script: its stiffness is not known)"
                                      : printf_string(" (not counting the %zu scripts: their stiffness is not known)",
                                                      report.scripts).c_str());
  if (b.poses.empty()) {
    out += "stiffness bound per pose: no pose of the grid is reachable\n";
  } else {
    out += printf_string("stiffness bound per pose (%zu poses of a %d x %d grid%s): lowest ", b.poses.size(), b.grid,
                         b.grid, b.held_poses > 0 ? printf_string(", %d past the condition limit left out", b.held_poses).c_str() : "") +
           pose_text(b.lowest) + ", highest " + pose_text(b.highest) + "\n";
  }
  const HarnessOptions& o = report.options;
  out += printf_string("hand %g N/m, %g N*s/m, %g g; sensor noise %s, seed %llu\n\n", o.hand_stiffness_N_per_m,
                       o.hand_damping_N_s_per_m, o.hand_mass_kg * 1e3,
                       o.noise_counts < 0 ? "from the profile" : printf_string("%g counts", o.noise_counts).c_str(),
                       static_cast<unsigned long long>(o.seed));
  out += "scenario  check          value           threshold        verdict  detail\n";
  if (!report.scene_checks.empty()) {
    out += padded("scene", 10) + "the environment as loaded\n";
    for (const CheckResult& c : report.scene_checks) out += format_check_row(c);
  }
  for (const PlanarScenarioResult& s : report.scenarios) {
    out += padded(s.scenario.name, 10) + s.scenario.description + "\n";
    if (!s.scenario.applicable) {
      out += padded("", 10) + "(not applicable)\n";
      continue;
    }
    for (const CheckResult& c : s.checks) out += format_check_row(c);
  }
  const Tally t = tally(report);
  out += t.failed == 0 ? "\nresult: pass (" + counted(t) + ")\n" : "\nresult: FAIL (" + failed_text(t) + ")\n";
  return out;
}

std::string format_planar_report_summary(const PlanarValidationReport& report) {
  std::vector<ReportSection> sections;
  if (!report.scene_checks.empty()) sections.push_back({"scene", "the environment as loaded", true, report.scene_checks});
  for (const PlanarScenarioResult& s : report.scenarios) {
    sections.push_back({s.scenario.name, s.scenario.description, s.scenario.applicable, s.checks});
  }
  return format_report_summary(report_table_header(format_planar_report_table(report)), sections);
}

json planar_report_to_json(const PlanarValidationReport& report) {
  const PlanarStiffnessBound& b = report.bound;
  json poses = json::array();
  for (const PlanarPoseBound& pose : b.poses) poses.push_back(pose_json(pose));
  const HarnessOptions& o = report.options;
  json out = {
      {"schema", kReportSchema},
      {"axes", 2},
      {"scene", {{"name", report.scene_name}, {"source", report.source_path}, {"rate_hz", report.rate_hz},
                 {"axes", 2}, {"shapes", report.shapes},
                 {"passivity_bound_N_per_m", b.poses.empty() ? json(nullptr) : json(b.lowest.bound_N_per_m)},
                 {"passivity_bound", b.poses.empty() ? json(nullptr) : json(b.lowest.name)},
                 {"stiffest_region_N_per_m", b.stiffest_N_per_m},
                 {"stiffness_bound", {{"grid", b.grid}, {"held_poses", b.held_poses},
                                      {"lowest", b.poses.empty() ? json(nullptr) : pose_json(b.lowest)},
                                      {"highest", b.poses.empty() ? json(nullptr) : pose_json(b.highest)},
                                      {"poses", poses}}},
                 {"load_warnings", report.load_warnings}}},
      {"options", {{"hand_stiffness_N_per_m", o.hand_stiffness_N_per_m},
                   {"hand_damping_N_s_per_m", o.hand_damping_N_s_per_m},
                   {"hand_mass_kg", o.hand_mass_kg},
                   {"noise_counts", o.noise_counts < 0 ? json(nullptr) : json(o.noise_counts)},
                   {"seed", o.seed},
                   {"free_start_m", o.free_start_planar_m ? vec(*o.free_start_planar_m) : json(nullptr)}}},
      {"pass", report.pass},
      {"scene_checks", json::array()},
      {"scenarios", json::array()}};
  for (const CheckResult& c : report.scene_checks) out["scene_checks"].push_back(check_to_json(c));
  for (const PlanarScenarioResult& s : report.scenarios) {
    const PlanarScenarioMetrics& m = s.metrics;
    json scenario = {{"name", s.scenario.name}, {"description", s.scenario.description},
                     {"applicable", s.scenario.applicable}, {"duration_s", s.scenario.duration_s},
                     {"start_m", vec(s.scenario.start_m)}, {"pass", s.pass}};
    if (s.scenario.applicable) {
      json script_faults = json::array();
      for (const auto& f : m.script_faults) script_faults.push_back({{"message", f.message}, {"where", f.where}});
      const bool popped = m.first_pop_t_s >= 0.0;
      json metrics = {
          {"ticks", m.ticks},
          {"max_requested_N", m.max_requested_N},
          {"max_output_N", m.max_output_N},
          {"max_output_x_m", vec(m.max_output_x_m)},
          {"max_output_t_s", m.max_output_t_s},
          {"time_at_limit_s", m.time_at_limit_s},
          {"time_at_limit_fraction", m.time_at_limit_fraction},
          {"max_slew_N_per_s", m.max_slew_N_per_s},
          {"force_jitter_N", m.force_jitter_N},
          {"jitter_peak_N", m.jitter_peak_N},
          {"jitter_peak_x_m", vec(m.jitter_peak_x_m)},
          {"jitter_peak_t_s", m.jitter_peak_t_s},
          {"passivity", {{"motor_work_J", m.passivity.motor_work_J}, {"stored_J", m.passivity.stored_J},
                         {"created_J", m.passivity.created_J}, {"dissipated_J", m.passivity.dissipated_J},
                         {"net_J", m.passivity.net_J}, {"ratio", m.passivity.ratio}, {"grows", m.passivity.grows}}},
          {"oscillation", nullptr},
          {"max_penetration_m", m.max_penetration_m},
          {"max_penetration_x_m", vec(m.max_penetration_x_m)},
          {"max_penetration_t_s", m.max_penetration_t_s},
          {"max_penetration_shape", m.max_penetration_shape < 0 ? json(nullptr) : json(m.max_penetration_shape)},
          {"pop_throughs", m.pop_throughs},
          {"first_pop_x_m", popped ? vec(m.first_pop_x_m) : json(nullptr)},
          {"first_pop_t_s", popped ? json(m.first_pop_t_s) : json(nullptr)},
          {"first_pop_shape", popped ? json(m.first_pop_shape) : json(nullptr)},
          {"pose_hold_ticks", m.pose_hold_ticks},
          {"pose_hold_force_ticks", m.pose_hold_force_ticks},
          {"max_condition", m.max_condition},
          {"max_condition_x_m", vec(m.max_condition_x_m)},
          {"max_condition_t_s", m.max_condition_t_s},
          {"script_errors", m.script_errors},
          {"script_budget_overruns", m.script_budget_overruns},
          {"script_faults", script_faults},
          {"tick_compute_s", {{"p50", m.compute_p50_s}, {"p99", m.compute_p99_s}, {"max", m.compute_max_s}}},
          {"safety", {{"nonfinite_faults", m.safety.nonfinite_faults},
                      {"outside_workspace_ticks", m.safety.outside_workspace_ticks},
                      {"soft_start_ticks", m.safety.soft_start_ticks},
                      {"clamped_ticks", m.safety.clamped_ticks},
                      {"slew_limited_ticks", m.safety.slew_limited_ticks},
                      {"pose_hold_ticks", m.safety.pose_hold_ticks},
                      {"motor_saturated_ticks", m.safety.motor_saturated_ticks}}}};
      if (m.oscillation) {
        const OscillationMetrics& w = *m.oscillation;
        metrics["oscillation"] = {{"from_s", w.from_s}, {"half_cycles", w.half_cycles},
                                  {"frequency_Hz", w.frequency_Hz}, {"initial_amplitude_m", w.initial_amplitude_m},
                                  {"residual_amplitude_m", w.residual_amplitude_m}, {"growth", w.growth},
                                  {"rest_m", vec(m.rest_m)}, {"major_axis", vec(m.major_axis)}};
      }
      scenario["metrics"] = metrics;
      json checks = json::array();
      for (const CheckResult& c : s.checks) checks.push_back(check_to_json(c));
      scenario["checks"] = checks;
    }
    out["scenarios"].push_back(scenario);
  }
  return out;
}

std::string planar_validation_figure_svg(const PlanarScene& scene, const PlanarValidationReport& report) {
  const PlanarScenarioResult* shown = nullptr;
  for (const PlanarScenarioResult& s : report.scenarios) {
    if (s.scenario.applicable && !s.pass) {
      shown = &s;
      break;
    }
  }
  for (const PlanarScenarioResult& s : report.scenarios) {
    if (shown == nullptr && s.scenario.applicable) shown = &s;
  }
  std::vector<PlanarTickRecord> records;
  std::string what = "no scenario run";
  std::string proxy_label;
  if (shown != nullptr) {
    // The proxy traced is a built-in shape's (a declared one has none); the run recorded
    // one point per scenario shape (planar_scenario_shapes), the built-in ones first.
    const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(scene);
    const int traced = nearest_shape_index(shapes, shown->scenario.start_m);
    const std::size_t recorded_per_tick = shown->records.empty() ? 0 : shown->proxies_m.size() / shown->records.size();
    if (traced >= 0) proxy_label = std::string("proxy of the ") + planar_shape_kind_name(shapes[static_cast<std::size_t>(traced)].kind);
    // Per bucket of whole ticks, its first tick and the one with the largest force.
    const std::size_t n = shown->records.size();
    const std::size_t per_bucket = std::max<std::size_t>(1, (n + kMaxPlanarTraceRecords / 2 - 1) / (kMaxPlanarTraceRecords / 2));
    auto record = [&](std::size_t k) {
      const PlanarValidateRecord& r = shown->records[k];
      PlanarTickRecord t;
      t.t_s = r.t_s;
      t.x_true_m = r.x_true_m;
      t.x_m = r.x_m;
      t.proxy_m = traced >= 0 ? shown->proxies_m[k * recorded_per_tick + static_cast<std::size_t>(traced)] : r.x_m;
      t.requested_N = r.requested_N;
      t.output_N = r.output_N;
      t.hand_N = r.hand_N;
      return t;
    };
    for (std::size_t begin = 0; begin < n; begin += per_bucket) {
      const std::size_t end = std::min(n, begin + per_bucket);
      std::size_t peak = begin;
      for (std::size_t k = begin; k < end; ++k) {
        if (norm(shown->records[k].output_N) > norm(shown->records[peak].output_N)) peak = k;
      }
      records.push_back(record(begin));
      if (peak != begin) records.push_back(record(peak));
    }
    what = shown->scenario.name + " (" + shown->scenario.description + ")" + (shown->pass ? "" : ", failing");
  }
  return planar_figure_svg(scene, PlanarFigureOptions{}, records, what, proxy_label);
}

}  // namespace hapscene
