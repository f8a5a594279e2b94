// `hapscene run ENV [ENV...]`: runs each environment on the device for a while, with a
// live status line on a terminal and a summary at the end of each; written once over N
// (what differs per device kind: run_kind.hpp).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/run_settings.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/run_session.hpp"
#include "engine/cli/run_kind.hpp"
#include "engine/cli/run_summary.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/cli/ui_option.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/reload_watcher.hpp"
#include "engine/run/runner.hpp"
#include "engine/run/script_fault_places.hpp"
#include "engine/run/telemetry_log.hpp"

namespace hapscene {
namespace {

std::atomic<bool> g_stop_requested{false};

extern "C" void on_interrupt(int /*signal*/) { g_stop_requested.store(true); }

RunSettings parse_settings(Arguments& arguments) {
  RunSettings settings;
  settings.device = arguments.take_value("device").value_or("sim");
  if (const auto baud = arguments.take(option::baud)) settings.link.baud = static_cast<int>(*baud);
  settings.options.duration_s = arguments.take(option::duration).value_or(settings.options.duration_s);
  if (arguments.take_flag("sim-time")) settings.options.pacing = Pacing::simulated_time;

  HandConfig& hand = settings.simulation.hand;
  // The hand's motion, hold and start points depend on the scene's axes: read after the
  // files, by the scene's kind (open_run_device, run_kind.hpp).
  settings.hand_text = arguments.take_value("hand");
  settings.hold_text = arguments.take_value("hold");
  settings.start_text = arguments.take_value("start");
  hand.stiffness_N_per_m = arguments.take(option::run_hand_stiffness).value_or(hand.stiffness_N_per_m);
  hand.damping_N_s_per_m = arguments.take(option::run_hand_damping).value_or(hand.damping_N_s_per_m);
  hand.release_s = arguments.take(option::release).value_or(hand.release_s);
  settings.noise_counts = arguments.take(option::noise).value_or(-1.0);
  settings.simulation.noise_seed = arguments.take(option::seed).value_or(settings.simulation.noise_seed);
  settings.quiet = arguments.take_flag("quiet");
  settings.reload = !arguments.take_flag("no-reload");
  if (const auto overruns = arguments.take_value("overruns")) {
    if (*overruns == "stop") {
      settings.options.overruns = OverrunResponse::stop;
    } else if (*overruns == "report") {
      settings.options.overruns = OverrunResponse::report;
    } else {
      arguments.fail("--overruns: unknown response \"" + printable(*overruns) + "\" (use stop or report)");
    }
  }
  settings.log_path = arguments.take_value("log");
  settings.plot_path = arguments.take_value("plot");
  return settings;
}

// Runs every environment (all of one N) on its device, one after the other: devices are
// opened first (a device that cannot be opened fails before anything moves), and a real
// board on a serial port is opened once and shared by every environment. After each run:
// the summary, the log, the figure, the device's report. Returns the exit code.
template <int N>
int run_environments(const Arguments& arguments, const RunSettings& settings, const std::vector<std::string>& files,
                     const std::vector<EnvironmentOf<N>>& environments) {
  std::vector<std::unique_ptr<DeviceOf<N>>> devices;
  std::vector<std::string> hands;  // the hand's name, for each environment
  const bool shared_device = settings.device.starts_with("serial");
  for (const EnvironmentOf<N>& environment : environments) {
    if (shared_device && !devices.empty()) {
      hands.push_back(hands.back());
      continue;
    }
    std::string hand;
    devices.push_back(open_run_device(arguments, settings, environment.scene, &hand));
    hands.push_back(hand);
  }

  const bool show_status = !settings.quiet && isatty(STDERR_FILENO) == 1;
  bool faulted = false;       // a run that ended on a fault makes the exit code 1
  bool write_failed = false;  // so does a --log file that could not be written
  for (std::size_t i = 0; i < environments.size() && !g_stop_requested.load(); ++i) {
    const SceneOf<N>& scene = environments[i].scene;
    DeviceOf<N>& device = *devices[shared_device ? 0 : i];
    // Observers (allocated before the run): the log, the figure's trace, where scripts faulted.
    const std::unique_ptr<TelemetryLogOf<N>> log = open_telemetry_log<N>(settings, scene.rate_hz);
    const std::unique_ptr<RunFigureOf<N>> figure =
        settings.plot_path ? open_run_figure(arguments, settings, scene, device) : nullptr;
    ScriptFaultPlaces<N> fault_places;
    const WatchedRun<N> run = run_watched<N>(scene, device, files[i], settings, show_status,
                                             {log.get(), figure ? figure->observer() : nullptr, &fault_places});
    if (i > 0) print_out("\n");
    print_run_summary<N>(scene, settings, hands[i], run.summary, &fault_places);
    if (run.reloads > 0) print_out("  reloads          %llu\n", static_cast<unsigned long long>(run.reloads));
    print_live_view_line(run);
    if (log && !finish_telemetry_log(*log, *settings.log_path)) write_failed = true;
    if (figure) {
      figure->write(*settings.plot_path, hands[i]);
      print_out("  plot             %s\n", printable(*settings.plot_path).c_str());
    }
    print_device_lines(device);
    write_out(device.report());
    flush_out();
    faulted = faulted || run_faulted(run, device);
  }
  return end_run(faulted || write_failed);
}

// The environments of one N, out of the loaded ones (all of that N).
template <int N>
std::vector<EnvironmentOf<N>> environments_of(std::vector<AnyEnvironment>* loaded) {
  std::vector<EnvironmentOf<N>> out;
  for (AnyEnvironment& environment : *loaded) out.push_back(std::move(std::get<EnvironmentOf<N>>(environment)));
  return out;
}

}  // namespace

int run_command(std::vector<std::string> args) {
  // The live view: --ui takes an optional value; a run with it lasts a day unless --duration says.
  const std::optional<UiAddress> ui = take_ui_option(&args, "hapscene run");
  const bool duration_given = option_given(args, "duration");
  Arguments arguments(std::move(args), "hapscene run");
  RunSettings settings = parse_settings(arguments);
  settings.ui = ui;
  if (ui && !duration_given) settings.options.duration_s = option::kDay_s;
  const std::vector<std::string> files = arguments.positionals();
  if (files.empty()) arguments.fail("expected at least one environment file");
  if (ui && files.size() != 1) arguments.fail("--ui takes one environment file");
  if (ui && settings.options.pacing == Pacing::simulated_time) arguments.fail("--ui: the live view is for real-time runs (drop --sim-time)");
  if ((settings.log_path || settings.plot_path) && files.size() != 1) {
    arguments.fail("--log and --plot take one environment file");
  }

  // Output files that would overwrite an input or each other, or cannot be written where
  // they are asked for, are refused before anything runs.
  {
    std::vector<std::pair<std::string, std::string>> outputs;
    if (settings.log_path) outputs.emplace_back("log", *settings.log_path);
    if (settings.plot_path) outputs.emplace_back("plot", *settings.plot_path);
    const std::string problem = output_path_problem(outputs, files);
    if (!problem.empty()) arguments.fail(problem);
  }

  // Ctrl-C or SIGTERM ends the run at the next tick, whatever its axes: the device is
  // closed the normal way (zero force, then the summary).
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  settings.options.stop_requested = &g_stop_requested;

  // Load everything first: a bad file fails before anything moves. A 2-DOF environment
  // runs alone (one file per run).
  std::vector<AnyEnvironment> loaded;
  for (const std::string& file : files) {
    loaded.push_back(load_any_environment(file));
    if (axes_of(loaded.back()) != 1 && files.size() != 1) {
      arguments.fail(file + ": a " + std::to_string(axes_of(loaded.back())) + "-DOF environment runs alone (one file per run)");
    }
  }
  const int axes = axes_of(loaded.front());
#define HAPSCENE_RUN_FOR(N) \
  if (axes == (N)) return run_environments<N>(arguments, settings, files, environments_of<N>(&loaded));
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_RUN_FOR)
#undef HAPSCENE_RUN_FOR
  return kExitFailure;  // not reached: every loaded environment has an N of the list
}

}  // namespace hapscene
