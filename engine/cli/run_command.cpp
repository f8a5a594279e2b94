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
#include "engine/cli/run_trace.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/harness/figures.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/live_status.hpp"
#include "engine/run/observer_list.hpp"
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

// Prints script log lines as they come, and "x, force, loop rate" on one terminal line
// ten times a second, until stopped.
class StatusLine {
 public:
  StatusLine(LiveStatus& status, double period_s, bool enabled)
      : status_(status), period_s_(period_s) {
    if (enabled) thread_ = std::thread([this] { loop(); });
  }
  ~StatusLine() {
    done_.store(true);
    if (thread_.joinable()) {
      thread_.join();
      std::fprintf(stderr, "\r\033[K");
    }
  }

 private:
  void loop() {
    using namespace std::chrono;
    std::uint64_t last_ticks = status_.ticks();
    auto last_time = steady_clock::now();
    while (!done_.load()) {
      std::this_thread::sleep_for(milliseconds(100));
      const auto now = steady_clock::now();
      const std::uint64_t ticks = status_.ticks();
      const double rate_hz = static_cast<double>(ticks - last_ticks) /
                             duration<double>(now - last_time).count();
      last_ticks = ticks;
      last_time = now;
      log_lines_.clear();
      status_.drain_log(&log_lines_);
      for (const std::string& line : log_lines_) std::fprintf(stderr, "\r\033[K%s\n", line.c_str());
      std::fprintf(stderr, "\r\033[K  t %7.3f s   x %+8.3f mm   force %+7.3f N   loop %8.1f Hz",
                   static_cast<double>(ticks) * period_s_, status_.x_m() * 1e3,
                   status_.output_N(), rate_hz);
      std::fflush(stderr);
    }
  }

  LiveStatus& status_;
  std::vector<std::string> log_lines_;
  double period_s_;
  std::atomic<bool> done_{false};
  std::thread thread_;
};

double us(std::uint64_t ns) { return static_cast<double>(ns) * 1e-3; }

// The force line with the limit in force at the end, and every limit a reload tightened.
void print_force_limits(const RunSummary& summary) {
  const SafetyConfig& start = summary.limits_at_start;
  const SafetyConfig& end = summary.limits_at_end;
  print_out("  max force        asked %.3f N, commanded %.3f N (limit %g N)\n",
            summary.max_abs_requested_N, summary.max_abs_output_N, end.max_force_N);
  std::string tightened;
  const auto note = [&](const char* name, double before, double after, const char* unit) {
    if (before == after) return;
    char item[128];
    std::snprintf(item, sizeof item, "%s%s %g -> %g %s", tightened.empty() ? "" : ", ", name, before, after, unit);
    tightened += item;
  };
  note("max force", start.max_force_N, end.max_force_N, "N");
  note("slew limit", start.slew_limit_N_per_s, end.slew_limit_N_per_s, "N/s");
  note("workspace min", start.workspace_min_m * 1e3, end.workspace_min_m * 1e3, "mm");
  note("workspace max", start.workspace_max_m * 1e3, end.workspace_max_m * 1e3, "mm");
  note("soft start", start.soft_start_s, end.soft_start_s, "s");
  note("soft-start threshold", start.soft_start_threshold_N, end.soft_start_threshold_N, "N");
  if (!tightened.empty()) print_out("  limits           tightened by a reload: %s\n", tightened.c_str());
}

void print_summary(const Scene& scene, const RunSettings& settings, const RunSummary& summary) {
  const bool real_time = settings.options.pacing == Pacing::real_time;
  // Names and paths from files and the command line are printed in printable form.
  print_out("%s (%s) on %s:%s, %g Hz, %s, hand %s\n", scene.name.c_str(),
            printable(scene.source_path).c_str(), printable(settings.device).c_str(),
            printable(scene.device.name).c_str(),
            scene.rate_hz, real_time ? "real time" : "simulated time",
            std::string(kHandMotionNames[static_cast<int>(settings.simulation.hand.motion)]).c_str());
  print_out("  ticks            %llu in %.3f s of device time, loop rate %.1f Hz\n",
            static_cast<unsigned long long>(summary.ticks), summary.device_time_s,
            summary.achieved_rate_hz);
  print_force_limits(summary);
  const SafetyCounters& safety = summary.safety;
  print_out("  time clamped     %.3f s (%llu ticks); slew-limited %llu, soft start %llu, "
            "outside workspace %llu ticks\n",
            static_cast<double>(safety.clamped_ticks) * scene.period_s,
            static_cast<unsigned long long>(safety.clamped_ticks),
            static_cast<unsigned long long>(safety.slew_limited_ticks),
            static_cast<unsigned long long>(safety.soft_start_ticks),
            static_cast<unsigned long long>(safety.outside_workspace_ticks));
  print_out("  faults           %llu non-finite forces\n",
            static_cast<unsigned long long>(safety.nonfinite_faults));
  for (const ScriptReport& script : summary.scripts) {
    if (script.disabled) {
      print_out("  script disabled  %s (at t = %.3f s; 0 N for the remaining %llu ticks)\n",
                printable(script.fault).c_str(), script.fault_time_s,
                static_cast<unsigned long long>(script.skipped_calls));
    } else {
      print_out("  script ok        %s\n", printable(script.name).c_str());
    }
  }
  print_out("  deadline misses  %s\n",
            real_time ? std::to_string(summary.deadline_misses).c_str() : "n/a (simulated time)");
  print_out("  tick compute     p50 %.2f us  p99 %.2f us  max %.2f us\n",
            us(summary.compute_ns.percentile_ns(0.50)), us(summary.compute_ns.percentile_ns(0.99)),
            us(summary.compute_ns.max_ns()));
  if (real_time) {
    print_out("  wake-up jitter   p50 %.2f us  p99 %.2f us  max %.2f us\n",
              us(summary.wake_late_ns.percentile_ns(0.50)),
              us(summary.wake_late_ns.percentile_ns(0.99)), us(summary.wake_late_ns.max_ns()));
    // The jitter histogram: ticks per band of lateness.
    const LatencyHistogram& late = summary.wake_late_ns;
    const std::uint64_t edges_ns[] = {10'000, 50'000, 100'000, 500'000, 1'000'000};
    std::uint64_t below = 0;
    std::string bands;
    const char* names[] = {"<10us", "10-50us", "50-100us", "100-500us", "0.5-1ms"};
    for (std::size_t b = 0; b < 5; ++b) {
      const std::uint64_t upto = late.count_at_most(edges_ns[b]);
      bands += std::string(b ? "  " : "") + names[b] + " " + std::to_string(upto - below);
      below = upto;
    }
    bands += "  >1ms " + std::to_string(late.count() - below);
    print_out("  jitter bands     %s\n", bands.c_str());
    print_out("  scheduling       %s\n", summary.realtime_note.c_str());
    if (summary.overrun_warnings > 0 || summary.overrun_fault) {  // (a window fault may come without a warning)
      print_out("  overruns         %llu warnings (first at %.3f s), longest streak %u misses, "
                "at most %u misses in %u deadlines\n",
                  static_cast<unsigned long long>(summary.overrun_warnings),
                  summary.first_overrun_warning_s, summary.longest_miss_streak, summary.most_misses_in_window,
                  settings.options.overrun_window_deadlines);
    }
    if (summary.overrun_fault_kind == OverrunFault::streak) {
      print_out("  FAULT            sustained overrun at %.3f s (%u deadline misses in a row): "
                  "zero force commanded, run stopped\n",
                  summary.overrun_fault_s, settings.options.overrun_fault_ticks);
    } else if (summary.overrun_fault_kind == OverrunFault::window) {
      print_out("  FAULT            frequent overruns at %.3f s (%u deadline misses within the last %u "
                  "deadlines, more than %u): zero force commanded, run stopped\n",
                  summary.overrun_fault_s, summary.most_misses_in_window,
                  settings.options.overrun_window_deadlines, settings.options.overrun_window_misses);
    }
  }
  flush_out();
}

}  // namespace

int run_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene run");
  RunSettings settings = parse_settings(arguments);
  const std::vector<std::string> files = arguments.positionals();
  if (files.empty()) arguments.fail("expected at least one environment file");
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

  std::signal(SIGINT, on_interrupt);
  settings.options.stop_requested = &g_stop_requested;
  const bool show_status = !settings.quiet && isatty(STDERR_FILENO) == 1;
  bool faulted = false;  // a run that ended on a fault makes the exit code 1
  bool write_failed = false;  // so does a --log file that could not be written
  for (std::size_t i = 0; i < scenes.size() && !g_stop_requested.load(); ++i) {
    const Scene& scene = scenes[i];
    Device& device = *devices[shared_device ? 0 : i];
    // Observers: the live status, and (allocated before the run) the log and the trace.
    LiveStatus status;
    ObserverList observers;
    observers.add(&status);
    const std::unique_ptr<TelemetryLog> log = open_telemetry_log<1>(settings, scene.rate_hz);
    observers.add(log.get());
    // The figure's trace: a fixed number of records, decimated for long runs.
    std::unique_ptr<RunTrace> trace;
    if (settings.plot_path) {
      const auto ticks = static_cast<std::uint64_t>(std::llround(settings.options.duration_s * scene.rate_hz));
      trace = std::make_unique<RunTrace>(device.truth(), ticks);
    }
    observers.add(trace.get());
    RunSummary summary;
    std::uint64_t replaced_script_faults = 0;
    SceneExchange exchange;
    RunOptions options = settings.options;
    if (settings.reload) options.reload = &exchange;
    {
      StatusLine line(status, scene.period_s, show_status);
      std::unique_ptr<ReloadWatcher> watcher;
      if (settings.reload) {
        ReloadWatcherOptions watch;
        watch.before_destroy = [&status](LoadedScene& retired) { status.drain_retired(retired); };
        watcher = std::make_unique<ReloadWatcher>(
            files[i], scene, &exchange, [show_status](const std::string& message) {
              std::fprintf(stderr, "%s%s\n", show_status ? "\r\033[K" : "", printable(message).c_str());
            }, std::move(watch));
      }
      summary = run_scene(scene, device, options, &observers);
      if (watcher) replaced_script_faults = watcher->replaced_script_faults();
    }
    std::vector<std::string> log_lines;
    status.drain_log(&log_lines);
    for (const std::string& line : log_lines) std::fprintf(stderr, "%s\n", printable(line).c_str());
    if (i > 0) print_out("\n");
    print_summary(scene, settings, summary);
    if (exchange.swaps() > 0) {
      print_out("  reloads          %llu\n", static_cast<unsigned long long>(exchange.swaps()));
    }
    if (log && !finish_telemetry_log(*log, *settings.log_path)) write_failed = true;
    if (trace) {
      std::string what = "run, hand " +
          std::string(kHandMotionNames[static_cast<int>(settings.simulation.hand.motion)]);
      if (trace->ticks_per_bucket() > 1) {
        what += ", lowest and highest force of every " + std::to_string(trace->ticks_per_bucket()) + " ticks";
      }
      write_output_file(*settings.plot_path, run_figure_svg(scene, trace->records(), what));
      print_out("  plot             %s\n", printable(*settings.plot_path).c_str());
    }
    write_out(device.report());
    flush_out();
    // A script disabled by a fault (in the version running at the end or in one a reload
    // replaced) is a fault the run saw: exit 1, like a device fault or a sustained overrun.
    const bool script_faulted =
        replaced_script_faults > 0 ||
        std::any_of(summary.scripts.begin(), summary.scripts.end(),
                    [](const ScriptReport& script) { return script.disabled; });
    faulted = faulted || summary.overrun_fault || device.fault_seen() || script_faulted;
  }
  // A reload load that never finished may still hold a thread: end without running
  // static destructors under it.
  if (ReloadWatcher::abandoned_loads() > 0) {
    const bool output_ok = report_stdout_failure();
    std::fflush(stderr);
    std::_Exit(faulted || write_failed || !output_ok ? kExitFailure : kExitOk);
  }
  return faulted || write_failed ? kExitFailure : kExitOk;
}

}  // namespace hapscene
