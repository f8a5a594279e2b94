#include "engine/harness/figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/harness/open_loop.hpp"
#include "engine/harness/pace.hpp"

namespace hapscene {
namespace {

const char* const kColors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b"};

std::vector<PlotLine> limit_lines(const Scene& scene) {
  char label[64];
  std::snprintf(label, sizeof label, "safety limit +/-%g N", scene.safety.max_force_N);
  // The axis scales to the forces drawn; the limit is drawn where it falls inside.
  PlotLine upper{scene.safety.max_force_N, label};
  PlotLine lower{-scene.safety.max_force_N, ""};
  upper.sets_range = lower.sets_range = false;
  return {upper, lower};
}

}  // namespace

PlotPanel force_displacement_panel(const Scene& scene, ScriptFaultLog* faults) {
  PlotPanel panel;
  panel.title = "force-displacement (open loop, after the safety clamp)";
  panel.x_label = "handle position x (mm)";
  panel.y_label = "force (N)";
  panel.lines = limit_lines(scene);
  // Scripts too slow for the loop are not drawn: 4001 points of them would take hours.
  if (const std::optional<CheckResult> pace = check_script_pace(scene)) {
    panel.title += ": not drawn, " + pace->detail;
    return panel;
  }

  // Velocities as a parameter only when some effect reads velocity.
  std::vector<double> velocities{0.0};
  if (scene.needs.velocity) velocities = {-0.1, -0.05, 0.0, 0.05, 0.1};
  const double margin_m = 0.002;
  const double low_m = scene.safety.workspace_min_m - margin_m;
  const double high_m = scene.safety.workspace_max_m + margin_m;
  // Every 50 um, or coarser in a wide workspace: at most 4001 points per curve.
  const double step_m = std::max(5e-5, (high_m - low_m) / 4000.0);
  std::vector<double> x_m;
  for (std::size_t i = 0;; ++i) {
    const double x = low_m + static_cast<double>(i) * step_m;
    if (x > high_m + 1e-12 || i > 4001) break;
    x_m.push_back(x);
  }
  // Each point as fresh script instances give it (see open_loop.hpp).
  OpenLoop open_loop(scene);
  PlotSeries asked{"asked (before the clamp), v = 0", "#999999", {}, {}, true};
  for (std::size_t i = 0; i < velocities.size(); ++i) {
    char label[64];
    std::snprintf(label, sizeof label, "v = %g m/s", velocities[i]);
    PlotSeries series{label, kColors[i % std::size(kColors)], {}, {}, false};
    OpenLoopScan scan;
    try {
      scan = open_loop.scan(x_m, velocities[i]);
    } catch (const ScriptsTooSlow& slow) {  // found too slow by the scan: as above
      panel.title += ": not drawn, " + std::string(slow.what());
      panel.series.clear();
      return panel;
    }
    for (std::size_t k = 0; k < x_m.size(); ++k) {
      const double force_N = scan.force_N[k];
      series.x.push_back(x_m[k] * 1e3);
      series.y.push_back(open_loop.output_N(x_m[k], force_N));
      if (velocities[i] == 0.0) {
        asked.x.push_back(x_m[k] * 1e3);
        asked.y.push_back(std::isfinite(force_N) ? force_N : 0.0);
      }
    }
    panel.series.push_back(std::move(series));
  }
  if (faults != nullptr) faults->merge(open_loop.faults());
  // Show what the scene asked for only where the clamp or the workspace cut it.
  bool differs = false;
  for (std::size_t i = 0; i < asked.y.size(); ++i) {
    const std::size_t zero_series = velocities.size() == 1 ? 0 : 2;
    differs = differs || asked.y[i] != panel.series[zero_series].y[i];
  }
  if (differs) {
    // Keep the axis readable: the asked curve is cut at twice the limit.
    for (double& y : asked.y) y = std::clamp(y, -2.0 * scene.safety.max_force_N, 2.0 * scene.safety.max_force_N);
    panel.series.push_back(std::move(asked));
  }
  return panel;
}

std::vector<PlotPanel> time_series_panels(const Scene& scene, const std::vector<TickRecord>& records,
                                          const std::string& what) {
  PlotPanel position{"position: " + what, "time t (s)", "position x (mm)", {}, {}};
  PlotPanel velocity{"velocity: " + what, "time t (s)", "velocity v (m/s)", {}, {}};
  PlotPanel force{"force: " + what, "time t (s)", "force (N)", {}, limit_lines(scene)};
  PlotSeries x_true{"x (simulated, true)", kColors[0], {}, {}, false};
  PlotSeries x_measured{"x (measured)", kColors[1], {}, {}, true};
  PlotSeries x_target{"hand target", kColors[2], {}, {}, true};
  PlotSeries v_true{"v (simulated, true)", kColors[0], {}, {}, false};
  PlotSeries v_estimated{"v (estimated)", kColors[1], {}, {}, true};
  PlotSeries asked{"asked by the scene", "#999999", {}, {}, true};
  PlotSeries output{"commanded (after safety)", kColors[3], {}, {}, false};
  PlotSeries hand{"hand on the handle", kColors[2], {}, {}, false};
  for (const TickRecord& r : records) {
    x_true.x.push_back(r.t_s), x_true.y.push_back(r.x_true_m * 1e3);
    x_measured.x.push_back(r.t_s), x_measured.y.push_back(r.x_m * 1e3);
    x_target.x.push_back(r.t_s), x_target.y.push_back(r.hand_target_m * 1e3);
    v_true.x.push_back(r.t_s), v_true.y.push_back(r.v_true_m_per_s);
    v_estimated.x.push_back(r.t_s), v_estimated.y.push_back(r.v_m_per_s);
    asked.x.push_back(r.t_s), asked.y.push_back(std::clamp(r.requested_N, -2.0 * scene.safety.max_force_N,
                                                           2.0 * scene.safety.max_force_N));
    output.x.push_back(r.t_s), output.y.push_back(r.output_N);
    hand.x.push_back(r.t_s), hand.y.push_back(r.hand_N);
  }
  position.series = {x_true, x_measured};
  // The hand's target motion, where a hand grips (NaN elsewhere breaks the line).
  if (std::any_of(x_target.y.begin(), x_target.y.end(), [](double y) { return std::isfinite(y); })) {
    position.series.push_back(std::move(x_target));
  }
  velocity.series = {v_true};
  if (scene.needs.velocity) velocity.series.push_back(v_estimated);
  force.series = {asked, output, hand};
  return {position, velocity, force};
}

PlotPanel run_force_position_panel(const Scene& scene, const std::vector<TickRecord>& records,
                                   const std::string& what) {
  PlotPanel panel{"force against position: " + what, "handle position x (mm)", "force (N)", {}, limit_lines(scene)};
  PlotSeries output{"commanded (after safety)", kColors[3], {}, {}, false};
  PlotSeries hand{"hand on the handle", kColors[2], {}, {}, false};
  for (const TickRecord& r : records) {
    output.x.push_back(r.x_true_m * 1e3), output.y.push_back(r.output_N);
    hand.x.push_back(r.x_true_m * 1e3), hand.y.push_back(r.hand_N);
  }
  panel.series = {output};
  if (std::any_of(hand.y.begin(), hand.y.end(), [](double y) { return y != 0.0; })) panel.series.push_back(hand);
  return panel;
}

std::string scene_figure_svg(const Scene& scene, const ScenarioResult& scenario, ScriptFaultLog* faults) {
  std::vector<PlotPanel> panels{force_displacement_panel(scene, faults)};
  if (scenario.scenario.applicable) {
    const std::string what = scenario.scenario.name + " (" + scenario.scenario.description + ")";
    for (PlotPanel& p : time_series_panels(scene, scenario.records, what)) panels.push_back(std::move(p));
    panels.push_back(run_force_position_panel(scene, scenario.records, what));
  }
  return render_svg(scene.name + " (" + scene.source_path + ") on " + scene.device.name, panels);
}

std::string validation_figure_svg(const Scene& scene, const ValidationReport& report) {
  const ScenarioResult* shown = nullptr;
  for (const ScenarioResult& s : report.scenarios) {
    if (!s.scenario.applicable) continue;
    if (shown == nullptr || (!s.pass && shown->pass)) shown = &s;
  }
  if (shown == nullptr) return render_svg(scene.name, {force_displacement_panel(scene)});
  return scene_figure_svg(scene, *shown);
}

std::string run_figure_svg(const Scene& scene, const std::vector<TickRecord>& records, const std::string& what) {
  std::vector<PlotPanel> panels{force_displacement_panel(scene)};
  for (PlotPanel& p : time_series_panels(scene, records, what)) panels.push_back(std::move(p));
  panels.push_back(run_force_position_panel(scene, records, what));
  return render_svg(scene.name + " (" + scene.source_path + ") on " + scene.device.name, panels);
}

}  // namespace hapscene
