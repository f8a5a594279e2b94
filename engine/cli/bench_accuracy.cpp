// `hapscene bench --accuracy [--svg FILE] [--rate HZ] [--axes 1|2]`: run time against error of the
// simulated Hapkit for each loop rate, plant integrator and substep count, with each
// scenario's Pareto front marked (table and SVG); then the 2-D rows: the integration
// error of the simulated 2-DOF plant for each kinematics family.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/bench/accuracy.hpp"
#include "engine/bench/planar_accuracy.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/devices/profile.hpp"
#include "engine/harness/svg_plot.hpp"

namespace hapscene {
namespace {

const char* scenario_name(AccuracyScenario s) { return s == AccuracyScenario::release ? "release" : "wall"; }

std::string percent(double fraction) {
  if (!std::isfinite(fraction)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f%%", 100.0 * fraction);
  return text;
}

void print_results(const std::vector<AccuracyResult>& results) {
  print_out("%-8s %7s %-6s %3s %10s %12s %11s %9s %9s %13s %s\n", "scenario", "rate_Hz", "integ", "sub",
            "ms_per_s", "pos_rms_um", "force_rms_mN", "freq_err", "decay_err", "integ_rms_um", "fronts");
  for (const AccuracyResult& r : results) {
    print_out("%-8s %7.0f %-6s %3d %10.3f %12.4g %11.4g %9s %9s %13.4g %s%s\n", scenario_name(r.which.scenario),
              r.which.rate_hz, std::string(kPlantIntegratorNames[static_cast<int>(r.which.integrator)]).c_str(),
              r.which.substeps, r.run_time_s_per_s * 1e3, r.finite ? r.position_rms_m * 1e6 : NAN,
              r.finite ? r.force_rms_N * 1e3 : NAN, percent(r.frequency_error).c_str(),
              percent(r.decay_error).c_str(), r.integration_rms_m * 1e6, r.front_truth ? "T" : "", r.front_integration ? "I" : "");
  }
}

// One panel: log10 error against log10 run time, one colour per integrator, the Pareto
// front as a dashed line. `rate_hz` 0: every loop rate; `integration`: the error against
// the fine integrator at the same rate, else against the truth.
PlotPanel accuracy_panel(const std::vector<AccuracyResult>& results, AccuracyScenario scenario,
                         double rate_hz, bool integration) {
  const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c"};
  PlotPanel panel;
  char title[160];
  if (integration) {
    std::snprintf(title, sizeof title, "%s at %g Hz: integration error (against 1 us RK4 at the same rate), 1..20 substeps",
                  scenario_name(scenario), rate_hz);
  } else {
    std::snprintf(title, sizeof title, "%s, 250 Hz .. 20 kHz: error against the %s", scenario_name(scenario),
                  scenario == AccuracyScenario::release ? "analytic oscillator" : "100 kHz reference");
  }
  panel.title = title;
  panel.x_label = "log10 run time (ms of CPU per simulated s)";
  panel.y_label = "log10 position RMS (um)";
  const auto selected = [&](const AccuracyResult& r) {
    return r.which.scenario == scenario && r.finite && (rate_hz == 0.0 || r.which.rate_hz == rate_hz);
  };
  const auto error_um = [&](const AccuracyResult& r) {
    return std::log10(std::max(1e-6, (integration ? r.integration_rms_m : r.position_rms_m) * 1e6));
  };
  for (int i = 0; i < 3; ++i) {
    PlotSeries s;
    s.label = std::string(kPlantIntegratorNames[i]);
    s.color = colors[i];
    s.markers = true;
    for (const AccuracyResult& r : results) {
      if (!selected(r) || static_cast<int>(r.which.integrator) != i) continue;
      s.x.push_back(std::log10(r.run_time_s_per_s * 1e3));
      s.y.push_back(error_um(r));
    }
    panel.series.push_back(std::move(s));
  }
  PlotSeries front;
  front.label = "Pareto front";
  front.color = "#333";
  front.dashed = true;
  std::vector<std::pair<double, double>> points;
  for (const AccuracyResult& r : results) {
    if (selected(r) && (integration ? r.front_integration : r.front_truth)) {
      points.push_back({std::log10(r.run_time_s_per_s * 1e3), error_um(r)});
    }
  }
  std::sort(points.begin(), points.end());
  for (const auto& [x, y] : points) front.x.push_back(x), front.y.push_back(y);
  panel.series.push_back(std::move(front));
  return panel;
}

std::string accuracy_svg(const std::vector<AccuracyResult>& results) {
  std::vector<PlotPanel> panels;
  for (const AccuracyScenario scenario : {AccuracyScenario::release, AccuracyScenario::wall}) {
    panels.push_back(accuracy_panel(results, scenario, 0.0, false));
    panels.push_back(accuracy_panel(results, scenario, 1000.0, true));
  }
  return render_svg("hapscene bench --accuracy: run time against error", panels, 900, 360);
}

// The 2-D rows: the planar plant's integration error (engine/bench/planar_accuracy.hpp)
// on each kinematics family's shipped profile, at the rates of the sweep `only_rate`
// leaves (0: all).
void print_planar_rows(double only_rate) {
  std::vector<PlanarAccuracyCase> cases = default_planar_accuracy_cases();
  if (only_rate > 0.0) std::erase_if(cases, [&](const PlanarAccuracyCase& c) { return c.rate_hz != only_rate; });
  print_out("integration error of the simulated 2-DOF plant (profiles haplink: serial 2R, haply2diy_v3: five-bar; "
            "their link, rotor and friction estimates)\n");
  print_out("release: 200 N/m spring to the home pose, released from (+8, -5) mm, no Coulomb friction, 1 s; "
            "circle: hand 500 N/m 5 N*s/m draws a 15 mm circle at 100 mm/s, no field, Coulomb on, 1.5 s; "
            "wall: hand 2000 N/m 10 N*s/m drives the handle diagonally at 100 mm/s into a 1000 N/m wall 10 mm away, "
            "10 mm beyond it, holds 0.1 s and back, Coulomb on\n");
  print_out("force from the true handle position, J^T F at that pose, held one tick (ideal sensors and drives); "
            "ms_per_s = CPU ms per simulated second (best of repeats); integ_rms / integ_max = handle position "
            "RMS / largest distance against the same loop rate with 1 us RK4 steps; travel = that run's handle "
            "path length\n\n");
  if (cases.empty()) {
    print_out("(no 2-D rows at this rate: the 2-D sweep runs 500, 1000, 2000 and 5000 Hz)\n");
    return;
  }
  print_out("%-13s %-8s %7s %-6s %3s %10s %12s %12s %9s\n", "device", "scenario", "rate_Hz", "integ", "sub", "ms_per_s",
            "integ_rms_um", "integ_max_um", "travel_mm");
  for (const char* name : {"haplink", "haply2diy_v3"}) {
    const PlanarProfile profile = load_planar_profile(name, ".");
    for (const PlanarAccuracyResult& r : run_planar_accuracy(planar_accuracy_device(profile), cases)) {
      print_out("%-13s %-8s %7.0f %-6s %3d %10.3f %12.4g %12.4g %9.2f\n", name,
                std::string(kPlanarAccuracyScenarioNames[static_cast<int>(r.which.scenario)]).c_str(), r.which.rate_hz,
                std::string(kPlanarIntegratorNames[static_cast<int>(r.which.integrator)]).c_str(), r.which.substeps,
                r.run_time_s_per_s * 1e3, r.finite ? r.integration_rms_m * 1e6 : NAN,
                r.finite ? r.integration_max_m * 1e6 : NAN, r.travel_m * 1e3);
    }
  }
}

}  // namespace

int bench_accuracy(Arguments& arguments) {
  const std::optional<std::string> svg = arguments.take_value("svg");
  const std::optional<double> only_rate = arguments.take(option::accuracy_rate);
  // --axes 1 or 2: only the 1-D (Hapkit) or the 2-D (planar plant) rows; both by default.
  const std::optional<std::uint64_t> only_axes = arguments.take(option::accuracy_axes);
  const std::vector<std::string> rest = arguments.positionals();
  if (!rest.empty()) arguments.fail("--accuracy takes no environment files");

  if (only_axes == 2u) {
    if (svg) arguments.fail("--svg: the figure is of the 1-D rows (leave out --axes 2)");
    if (only_rate && *only_rate != 500.0 && *only_rate != 1000.0 && *only_rate != 2000.0 && *only_rate != 5000.0) {
      arguments.fail("--rate: the 2-D rows run at 500, 1000, 2000 or 5000 Hz");
    }
    print_planar_rows(only_rate.value_or(0.0));
    return 0;
  }
  const DeviceProfile profile = load_device_profile("hapkit3", ".");
  const AccuracySetup setup = accuracy_setup(profile);
  std::vector<AccuracyCase> cases = default_accuracy_cases();
  if (only_rate) std::erase_if(cases, [&](const AccuracyCase& c) { return c.rate_hz != *only_rate; });
  if (cases.empty()) arguments.fail("--rate: not one of 250, 500, 1000, 2000, 5000, 10000, 20000 Hz");

  print_out("run time against error of the simulated Hapkit (profile hapkit3: m %g kg, b %g N*s/m)\n",
            setup.mass_kg, setup.viscous_N_s_per_m);
  print_out("release: %g N/m spring from %g mm, no Coulomb friction; analytic %.4f Hz, decay %.4f 1/s\n",
            setup.spring_N_per_m, setup.start_m * 1e3, setup.analytic_frequency_Hz, setup.analytic_decay_per_s);
  print_out("wall: %g N/m at %g mm, hand %g N/m %g N*s/m at %g mm/s in and out, Coulomb on; truth = 100 kHz "
            "loop, RK4 at 1 us\n",
            setup.wall_N_per_m, setup.wall_m * 1e3, setup.hand_N_per_m, setup.hand_N_s_per_m,
            setup.speed_m_per_s * 1e3);
  print_out("force rendered from the true position and held one tick (ideal sensor and motor); ms_per_s = "
            "CPU ms per simulated second (best of repeats); integ_rms = position RMS against the same loop "
            "rate with 1 us RK4 steps; fronts: T = on the scenario's Pareto front of run time against pos_rms, "
            "I = on the front of run time against integ_rms at this loop rate\n\n");
  std::vector<AccuracyResult> results = run_accuracy_sweep(profile, cases);
  print_results(results);
  if (!only_axes) {
    print_out("\n");
    print_planar_rows(only_rate.value_or(0.0));
  }
  if (svg) {
    write_output_file(*svg, accuracy_svg(results));
    print_out("\nwrote %s\n", svg->c_str());
  }
  return 0;
}

}  // namespace hapscene
