#include "engine/cli/run_settings.hpp"

#include <unistd.h>

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
#include "engine/cli/planar_run_hand.hpp"
#include "engine/cli/run_session.hpp"
#include "engine/cli/run_summary.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/devices/planar/planar_hand.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/harness/planar_figure.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/planar_trace.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/script_fault_places.hpp"
#include "engine/run/telemetry_log.hpp"

namespace hapscene {
namespace {

// The hand of a planar run: --hand over the scene's workspace box (planar_run_hand.hpp),
// holding or releasing at --hold (default the start).
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
  const Vec2 hold_m =
      settings.hold_text ? parse_planar_point(arguments, "hold", *settings.hold_text, option::hold) : start_m;
  // A hold the linkage cannot reach would pin the handle against its stops.
  if (settings.hold_text) {
    try {
      (void)planar_joint_angles_at(scene.device, hold_m);
    } catch (const InputError& error) {
      arguments.fail(std::string("--hold: ") + error.what());
    }
  }
  return planar_run_hand(scene, hand.motion, settings.simulation.hand, hold_m);
}

}  // namespace

int run_planar(const Arguments& arguments, const RunSettings& settings, const std::string& file) {
  // (Output paths were checked by run_command: none overwrites an input or another.)
  if (settings.noise_counts >= 0.0) arguments.fail("--noise: not yet for a 2-DOF environment");
  const PlanarScene scene = load_planar_environment_file(file);
  // The simulated linkage, alone or under two simulated boards: the hand and simulated time apply.
  const bool simulated = simulates_plant(settings.device);
  if (!simulated && (settings.hand_text || settings.hold_text || settings.start_text)) {
    arguments.fail(std::string(settings.hand_text ? "--hand" : settings.hold_text ? "--hold" : "--start") +
                   ": the simulated device's option; --device " + settings.device + " is a real one");
  }
  if (!simulated && settings.options.pacing == Pacing::simulated_time) {
    arguments.fail("--sim-time: --device " + settings.device + " is a real device, which runs in real time");
  }

  // Where the handle starts: --start, else the profile's home.
  const Vec2 start_m =
      settings.start_text ? parse_planar_point(arguments, "start", *settings.start_text, option::run_start) : scene.device.home_m;
  PlanarSimulationConfig simulation;
  if (simulated) simulation.hand = planar_hand(arguments, settings, scene, start_m);
  simulation.noise_seed = settings.simulation.noise_seed;
  std::unique_ptr<DeviceOf<2>> device;
  if (simulated) {
    try {
      simulation.start_q_rad = planar_joint_angles_at(scene.device, start_m);
    } catch (const InputError& error) {
      arguments.fail(std::string("--start: ") + error.what());
    }
  }
  try {
    device = open_planar_device(settings.device, scene.device, simulation, settings.link);
  } catch (const InputError& error) {
    arguments.fail(error.what());
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
  ScriptFaultPlaces<2> fault_places;
  const bool show_status = !settings.quiet && isatty(STDERR_FILENO) == 1;
  const WatchedRun<2> run =
      run_watched<2>(scene, *device, file, settings, show_status, {log.get(), trace.get(), &fault_places});
  const RunSummaryOf<2>& summary = run.summary;
  const std::string hand = simulated ? std::string(kPlanarHandMotionNames[static_cast<int>(simulation.hand.motion)])
                                     : std::string("yours");
  print_run_summary<2>(scene, settings, hand, summary, &fault_places);
  if (run.reloads > 0) print_out("  reloads          %llu\n", static_cast<unsigned long long>(run.reloads));
  print_live_view_line(run);
  const bool write_failed = log && !finish_telemetry_log(*log, *settings.log_path);
  if (trace) {
    std::string what = "run, hand " + hand;
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
  // The device's report: the simulated plant's, and the links of a device on boards.
  if (const PlanarPlant* plant = simulated_planar_plant(*device)) {
    print_out("  plant            %llu linkage faults (the linkage at the edge of closing)\n",
              static_cast<unsigned long long>(plant->linkage_faults()));
  }
  write_out(device->report());
  flush_out();
  return end_run(run_faulted(run, *device) || write_failed);
}

}  // namespace hapscene
