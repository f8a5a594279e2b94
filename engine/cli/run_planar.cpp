#include "engine/cli/run_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/planar/planar_hand.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/harness/planar_figure.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/planar_trace.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/observer_list.hpp"
#include "engine/run/telemetry_log.hpp"

namespace hapscene {
namespace {

// The hand of a planar run: its motion over the scene's workspace box (a sweep covers the
// middle 80 % of it; a line crosses it; a circle of a quarter of its smaller side turns
// round its middle), holding or releasing at --hold (default the start).
PlanarHandConfig planar_hand(const Arguments& arguments, const RunSettings& settings, const PlanarScene& scene,
                             const Vec2& start_m) {
  PlanarHandConfig hand;
  hand.motion = PlanarHandMotion::sweep;
  if (const auto& motion = settings.hand_text) {
    const auto* found = std::find(std::begin(kPlanarHandMotionNames), std::end(kPlanarHandMotionNames), *motion);
    if (found == std::end(kPlanarHandMotionNames) || *found == "path") {
      arguments.fail("--hand: unknown motion \"" + *motion +
                     "\" (a 2-DOF run takes sweep, line, circle, hold, release, shake or none)");
    }
    hand.motion = static_cast<PlanarHandMotion>(found - std::begin(kPlanarHandMotionNames));
  }
  hand.stiffness_N_per_m = settings.simulation.hand.stiffness_N_per_m;
  hand.damping_N_s_per_m = settings.simulation.hand.damping_N_s_per_m;
  hand.release_s = settings.simulation.hand.release_s;
  hand.hold_m = settings.hold_text ? parse_planar_point(arguments, "hold", *settings.hold_text, option::hold) : start_m;
  const Vec2 low = scene.safety.workspace_min_m;
  const Vec2 high = scene.safety.workspace_max_m;
  const Vec2 middle = (low + high) * 0.5;
  const Vec2 margin = (high - low) * 0.1;
  hand.sweep_min_m = low + margin;
  hand.sweep_max_m = high - margin;
  hand.line_from_m = Vec2{{low[0] + margin[0], middle[1]}};
  hand.line_to_m = Vec2{{high[0] - margin[0], middle[1]}};
  hand.line_back_and_forth = true;
  hand.circle_center_m = middle;
  hand.circle_radius_m = 0.25 * std::min(high[0] - low[0], high[1] - low[1]);
  return hand;
}

void print_planar_summary(const PlanarScene& scene, const RunSettings& settings, const PlanarHandConfig& hand,
                          const RunSummaryOf<2>& summary, const SimulatedPlanar& device) {
  const bool real_time = settings.options.pacing == Pacing::real_time;
  print_out("%s (%s) on %s:%s, %g Hz, %s, hand %s\n", scene.name.c_str(), printable(scene.source_path).c_str(),
            printable(settings.device).c_str(), printable(scene.device.name).c_str(), scene.rate_hz,
            real_time ? "real time" : "simulated time",
            std::string(kPlanarHandMotionNames[static_cast<int>(hand.motion)]).c_str());
  print_out("  ticks            %llu in %.3f s of device time, loop rate %.1f Hz\n",
            static_cast<unsigned long long>(summary.ticks), summary.device_time_s, summary.achieved_rate_hz);
  print_out("  max force        asked %.3f N, commanded %.3f N (limit %g N, magnitudes)\n",
            summary.max_abs_requested_N, summary.max_abs_output_N, summary.limits_at_end.max_force_N);
  const SafetyCounters& safety = summary.safety;
  const auto ticks = [](std::uint64_t n) { return static_cast<unsigned long long>(n); };
  print_out("  time clamped     %.3f s (%llu ticks); slew-limited %llu, soft start %llu, "
            "outside workspace %llu ticks\n",
            static_cast<double>(safety.clamped_ticks) * scene.period_s, ticks(safety.clamped_ticks),
            ticks(safety.slew_limited_ticks), ticks(safety.soft_start_ticks), ticks(safety.outside_workspace_ticks));
  print_out("  linkage          %llu ticks near a singular pose or unreachable (force held), "
            "%llu with a saturated motor (both scaled)\n",
            ticks(safety.pose_hold_ticks), ticks(safety.motor_saturated_ticks));
  print_out("  faults           %llu non-finite forces\n", ticks(safety.nonfinite_faults));
  for (const ScriptReport& script : summary.scripts) {
    if (script.disabled) {
      print_out("  script disabled  %s (at t = %.3f s; 0 N for the remaining %llu ticks)\n",
                printable(script.fault).c_str(), script.fault_time_s, ticks(script.skipped_calls));
    } else {
      print_out("  script ok        %s\n", printable(script.name).c_str());
    }
  }
  print_out("  tick compute     p50 %.2f us  p99 %.2f us  max %.2f us\n",
            static_cast<double>(summary.compute_ns.percentile_ns(0.50)) * 1e-3,
            static_cast<double>(summary.compute_ns.percentile_ns(0.99)) * 1e-3,
            static_cast<double>(summary.compute_ns.max_ns()) * 1e-3);
  print_out("  plant            %llu linkage faults (the five-bar at the edge of closing)\n",
            ticks(device.plant().linkage_faults()));
}

}  // namespace

int run_planar(const Arguments& arguments, const RunSettings& settings, const std::string& file) {
  if (settings.device != "sim") {
    arguments.fail("--device " + settings.device +
                   ": a 2-DOF environment runs on the simulated device only (--device sim) so far");
  }
  // (Output paths were checked by run_command: none overwrites an input or another.)
  if (settings.noise_counts >= 0.0) arguments.fail("--noise: not yet for a 2-DOF environment");
  const PlanarScene scene = load_planar_environment_file(file);

  // Where the handle starts: --start, else the profile's home.
  const Vec2 start_m =
      settings.start_text ? parse_planar_point(arguments, "start", *settings.start_text, option::run_start) : scene.device.home_m;
  PlanarSimulationConfig simulation;
  simulation.hand = planar_hand(arguments, settings, scene, start_m);
  simulation.noise_seed = settings.simulation.noise_seed;
  std::unique_ptr<SimulatedPlanar> device;
  try {
    simulation.start_q_rad = planar_joint_angles_at(scene.device, start_m);
    device = std::make_unique<SimulatedPlanar>(scene.device, simulation);
  } catch (const InputError& error) {
    arguments.fail(std::string("--start: ") + error.what());
  }

  const std::unique_ptr<TelemetryLogOf<2>> log = open_telemetry_log<2>(settings, scene.rate_hz);
  // The figure's trace (allocated before the run): the handle and the proxy of the shape
  // nearest the start.
  std::unique_ptr<PlanarTrace> trace;
  int proxy_index = -1;
  if (settings.plot_path) {
    proxy_index = nearest_shape_index(planar_shape_list(scene), start_m);
    const auto ticks = static_cast<std::uint64_t>(std::llround(settings.options.duration_s * scene.rate_hz));
    trace = std::make_unique<PlanarTrace>(device->truth(), ticks, proxy_index);
  }
  ObserverListOf<2> observers;
  observers.add(log.get());
  observers.add(trace.get());
  RunOptions options = settings.options;
  options.reload = nullptr;  // hot reload: 1-DOF scenes only, so far
  const RunSummaryOf<2> summary = run_scene(scene, *device, options, &observers);
  print_planar_summary(scene, settings, simulation.hand, summary, *device);
  const bool write_failed = log && !finish_telemetry_log(*log, *settings.log_path);
  if (trace) {
    std::string what = "run, hand " + std::string(kPlanarHandMotionNames[static_cast<int>(simulation.hand.motion)]);
    if (trace->ticks_per_bucket() > 1) {
      what += ", first tick and highest force of every " + std::to_string(trace->ticks_per_bucket()) + " ticks";
    }
    const std::string proxy_label =
        proxy_index >= 0 ? std::string("proxy of the ") +
                               planar_shape_kind_name(planar_shape_list(scene)[static_cast<std::size_t>(proxy_index)].kind)
                         : std::string();
    write_output_file(*settings.plot_path, planar_figure_svg(scene, PlanarFigureOptions{}, trace->records(), what,
                                                             proxy_label));
    print_out("  plot             %s\n", printable(*settings.plot_path).c_str());
  }
  flush_out();
  // A script disabled by a fault is a fault the run saw (exit 1), as in 1-D.
  const bool script_faulted = std::any_of(summary.scripts.begin(), summary.scripts.end(),
                                          [](const ScriptReport& script) { return script.disabled; });
  const bool faulted = summary.overrun_fault || summary.safety.nonfinite_faults > 0 || script_faulted;
  return faulted || write_failed ? kExitFailure : kExitOk;
}

}  // namespace hapscene
