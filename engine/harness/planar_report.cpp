#include "engine/harness/planar_report.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/format.hpp"
#include "engine/harness/planar_figure.hpp"
#include "engine/harness/report.hpp"
#include "engine/harness/report_parts.hpp"

namespace hapscene {
namespace {

using nlohmann::json;

json vec(const Vec2& v) { return position_json(v); }

constexpr const char* kPlanarSceneDescription = "the environment as loaded";

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

std::string format_report_line(const PlanarValidationReport& report) {
  return format_report_line(report.scene_name, report.source_path, report_sections(report, kPlanarSceneDescription));
}

std::string format_report_table(const PlanarValidationReport& report) {
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
  out += format_hand_line(report.options);
  return out + format_report_rows(report_sections(report, kPlanarSceneDescription));
}

std::string format_report_summary(const PlanarValidationReport& report) {
  return format_report_summary(report_table_header(format_report_table(report)),
                               report_sections(report, kPlanarSceneDescription));
}

json report_to_json(const PlanarValidationReport& report) {
  const PlanarStiffnessBound& b = report.bound;
  json poses = json::array();
  for (const PlanarPoseBound& pose : b.poses) poses.push_back(pose_json(pose));
  json options = options_json(report.options);
  options["free_start_m"] = report.options.free_start_planar_m ? vec(*report.options.free_start_planar_m) : json(nullptr);
  json out = report_json_frame(
      report,
      {{"name", report.scene_name}, {"source", report.source_path}, {"rate_hz", report.rate_hz},
       {"axes", 2}, {"shapes", report.shapes},
       {"passivity_bound_N_per_m", b.poses.empty() ? json(nullptr) : json(b.lowest.bound_N_per_m)},
       {"passivity_bound", b.poses.empty() ? json(nullptr) : json(b.lowest.name)},
       {"stiffest_region_N_per_m", b.stiffest_N_per_m},
       {"stiffness_bound", {{"grid", b.grid}, {"held_poses", b.held_poses},
                            {"lowest", b.poses.empty() ? json(nullptr) : pose_json(b.lowest)},
                            {"highest", b.poses.empty() ? json(nullptr) : pose_json(b.highest)},
                            {"poses", poses}}}},
      options);
  out["axes"] = 2;
  for (const PlanarScenarioResult& s : report.scenarios) {
    const PlanarScenarioMetrics& m = s.metrics;
    const bool popped = m.first_pop_t_s >= 0.0;
    json metrics = shared_metrics_json(m);
    metrics["max_penetration_t_s"] = m.max_penetration_t_s;
    metrics["max_penetration_shape"] = m.max_penetration_shape < 0 ? json(nullptr) : json(m.max_penetration_shape);
    metrics["pop_throughs"] = m.pop_throughs;
    metrics["first_pop_x_m"] = popped ? vec(m.first_pop_x_m) : json(nullptr);
    metrics["first_pop_t_s"] = popped ? json(m.first_pop_t_s) : json(nullptr);
    metrics["first_pop_shape"] = popped ? json(m.first_pop_shape) : json(nullptr);
    metrics["pose_hold_ticks"] = m.pose_hold_ticks;
    metrics["pose_hold_force_ticks"] = m.pose_hold_force_ticks;
    metrics["max_condition"] = m.max_condition;
    metrics["max_condition_x_m"] = vec(m.max_condition_x_m);
    metrics["max_condition_t_s"] = m.max_condition_t_s;
    metrics["safety"]["pose_hold_ticks"] = m.safety.pose_hold_ticks;
    metrics["safety"]["motor_saturated_ticks"] = m.safety.motor_saturated_ticks;
    if (m.oscillation) {
      metrics["oscillation"] = oscillation_json(*m.oscillation);
      metrics["oscillation"]["rest_m"] = vec(m.rest_m);
      metrics["oscillation"]["major_axis"] = vec(m.major_axis);
    }
    json scenario = scenario_json(s, metrics);
    scenario["start_m"] = vec(s.scenario.start_m);
    out["scenarios"].push_back(scenario);
  }
  return out;
}

std::string validation_figure_svg(const PlanarScene& scene, const PlanarValidationReport& report) {
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
