// `hapscene run ENV [ENV...]`: runs each environment on the device for a while, with a
// live status line on a terminal and a summary at the end of each.
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
#include "engine/cli/run_summary.hpp"
#include "engine/cli/run_trace.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/cli/ui_option.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/harness/figures.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/reload_watcher.hpp"
#include "engine/run/runner.hpp"
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
  // files (parse_capstan_hand, or the planar run's own).
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

// The 1-DOF hand: --hand, --hold X, --start X.
void parse_capstan_hand(const Arguments& arguments, RunSettings* settings) {
  HandConfig& hand = settings->simulation.hand;
  if (const auto& motion = settings->hand_text) {
    const auto* found = std::find(std::begin(kHandMotionNames), std::end(kHandMotionNames), *motion);
    if (found == std::end(kHandMotionNames) || *found == "path") {
      arguments.fail("--hand: unknown motion \"" + *motion + "\" (use sweep, hold, release, shake or none)");
    }
    hand.motion = static_cast<HandMotion>(found - std::begin(kHandMotionNames));
  }
  if (settings->hold_text) hand.hold_m = parse_option_quantity(*settings->hold_text, option::hold, "hapscene run: --hold");
  if (settings->start_text) {
    settings->simulation.start_x_m = parse_option_quantity(*settings->start_text, option::run_start, "hapscene run: --start");
  }
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

  // A 2-DOF environment runs alone, on its own path (run_planar.cpp).
  for (const std::string& file : files) {
    if (environment_axes(file) != 2) continue;
    if (files.size() != 1) arguments.fail(file + ": a 2-DOF environment runs alone (one file per run)");
    return run_planar(arguments, settings, file);
  }
  parse_capstan_hand(arguments, &settings);

  // Load everything and open every device first: a bad file fails before anything moves.
  // A real board on a serial port is opened once and shared by every environment.
  std::vector<Scene> scenes;
  std::vector<std::unique_ptr<Device>> devices;
  const bool shared_device = settings.device.starts_with("serial");
  for (const std::string& file : files) {
    scenes.push_back(load_environment_file(file));
    if (shared_device && !devices.empty()) continue;
    DeviceProfile profile = scenes.back().device;
    if (settings.noise_counts >= 0.0) profile.plant.sensor_noise_counts = settings.noise_counts;
    try {
      devices.push_back(open_device(settings.device, profile, settings.simulation, settings.link));
    } catch (const InputError& error) {
      arguments.fail(error.what());
    }
  }

  const bool show_status = !settings.quiet && isatty(STDERR_FILENO) == 1;
  bool faulted = false;  // a run that ended on a fault makes the exit code 1
  bool write_failed = false;  // so does a --log file that could not be written
  for (std::size_t i = 0; i < scenes.size() && !g_stop_requested.load(); ++i) {
    const Scene& scene = scenes[i];
    Device& device = *devices[shared_device ? 0 : i];
    // Observers (allocated before the run): the log and the trace.
    const std::unique_ptr<TelemetryLog> log = open_telemetry_log<1>(settings, scene.rate_hz);
    // The figure's trace: a fixed number of records, decimated for long runs.
    std::unique_ptr<RunTrace> trace;
    if (settings.plot_path) {
      const auto ticks = static_cast<std::uint64_t>(std::llround(settings.options.duration_s * scene.rate_hz));
      trace = std::make_unique<RunTrace>(device.truth(), ticks);
    }
    const WatchedRun<1> run = run_watched<1>(scene, device, files[i], settings, show_status, {log.get(), trace.get()});
    const RunSummary& summary = run.summary;
    if (i > 0) print_out("\n");
    const std::string hand(kHandMotionNames[static_cast<int>(settings.simulation.hand.motion)]);
    print_run_summary<1>(scene, settings, hand, summary, nullptr);
    if (run.reloads > 0) print_out("  reloads          %llu\n", static_cast<unsigned long long>(run.reloads));
    print_live_view_line(run);
    if (log && !finish_telemetry_log(*log, *settings.log_path)) write_failed = true;
    if (trace) {
      std::string what = "run, hand " + hand;
      if (trace->ticks_per_bucket() > 1) {
        what += ", lowest and highest force of every " + std::to_string(trace->ticks_per_bucket()) + " ticks";
      }
      write_output_file(*settings.plot_path, run_figure_svg(scene, trace->records(), what));
      print_out("  plot             %s\n", printable(*settings.plot_path).c_str());
    }
    write_out(device.report());
    flush_out();
    faulted = faulted || run_faulted(run, device);
  }
  return end_run(faulted || write_failed);
}

}  // namespace hapscene
