#pragma once
// One environment's run as `hapscene run` does it, whatever the scene's axes: the live
// status line and the scripts' log() lines on stderr, hot reload of the environment and
// its scripts (unless --no-reload), the caller's observers (telemetry log, plot trace),
// and the log lines still queued at the end printed once, after the run. run_command.cpp
// prints the summary and the outputs after it, for every N.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/run_settings.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/run/live_status.hpp"
#include "engine/run/observer_list.hpp"
#include "engine/run/reload_watcher.hpp"
#include "engine/run/runner.hpp"
#include "engine/serve/live_view.hpp"

namespace hapscene {

// Prints script log lines as they come, and the handle, force and loop rate on one
// terminal line ten times a second, until destroyed (nothing when not enabled).
template <int N>
class StatusLine {
 public:
  // `view` (may be null): the live view, which gets the log lines too; with one, the log
  // lines are printed as they come even when the status line is not shown.
  StatusLine(LiveStatusOf<N>& status, double period_s, bool enabled, LiveViewOf<N>* view = nullptr)
      : status_(status), period_s_(period_s), enabled_(enabled), view_(view) {
    if (enabled || view != nullptr) thread_ = std::thread([this] { loop(); });
  }
  ~StatusLine() {
    {
      std::lock_guard lock(done_mutex_);
      done_.store(true);
    }
    done_wake_.notify_all();  // the run ends now, not up to a refresh period later
    if (thread_.joinable()) {
      thread_.join();
      if (enabled_) std::fprintf(stderr, "\r\033[K");
    }
  }
  StatusLine(const StatusLine&) = delete;
  StatusLine& operator=(const StatusLine&) = delete;

 private:
  void loop() {
    using namespace std::chrono;
    std::uint64_t last_ticks = status_.ticks();
    auto last_time = steady_clock::now();
    for (;;) {
      {
        std::unique_lock lock(done_mutex_);
        if (done_wake_.wait_for(lock, milliseconds(100), [this] { return done_.load(); })) break;
      }
      const auto now = steady_clock::now();
      const std::uint64_t ticks = status_.ticks();
      const double rate_hz = static_cast<double>(ticks - last_ticks) / duration<double>(now - last_time).count();
      last_ticks = ticks;
      last_time = now;
      log_lines_.clear();
      status_.drain_log(&log_lines_);
      for (const std::string& line : log_lines_) {
        if (enabled_) {
          std::fprintf(stderr, "\r\033[K%s\n", line.c_str());
        } else {
          std::fprintf(stderr, "%s\n", printable(line).c_str());  // as after the run
        }
        if (view_ != nullptr) view_->add_log(line);
      }
      if (!enabled_) continue;
      const double t_s = static_cast<double>(ticks) * period_s_;
      if constexpr (N == 1) {
        std::fprintf(stderr, "\r\033[K  t %7.3f s   x %+8.3f mm   force %+7.3f N   loop %8.1f Hz", t_s,
                     status_.x_m() * 1e3, status_.output_N(), rate_hz);
      } else {
        const Axes<N> x_m = status_.x_m();
        std::fprintf(stderr, "\r\033[K  t %7.3f s   x %+8.3f mm   y %+8.3f mm   force %7.3f N   loop %8.1f Hz", t_s,
                     x_m[0] * 1e3, x_m[1] * 1e3, norm(status_.output_N()), rate_hz);
      }
      std::fflush(stderr);
    }
  }

  LiveStatusOf<N>& status_;
  std::vector<std::string> log_lines_;
  double period_s_;
  bool enabled_;
  LiveViewOf<N>* view_;
  std::atomic<bool> done_{false};
  std::mutex done_mutex_;
  std::condition_variable done_wake_;
  std::thread thread_;
};

template <int N>
struct WatchedRun {
  RunSummaryOf<N> summary;
  std::uint64_t reloads{};                 // versions the loop took
  std::uint64_t replaced_script_faults{};  // disabled scripts in versions a reload replaced
  bool live_view{};                        // --ui: the live view's counts
  std::uint64_t live_events{};
  std::uint64_t live_dropped_events{};
  std::uint64_t live_dropped_ticks{};
};

// The summary's line for the live view, when there was one.
template <int N>
void print_live_view_line(const WatchedRun<N>& run) {
  if (!run.live_view) return;
  print_out("  live view        %llu events, %llu dropped by slow clients, %llu ticks dropped (ring full)\n",
            static_cast<unsigned long long>(run.live_events), static_cast<unsigned long long>(run.live_dropped_events),
            static_cast<unsigned long long>(run.live_dropped_ticks));
}

// Runs `scene` (loaded from `file`) on `device` for settings.options. `observers`: the
// caller's (null ones are skipped), after the live status.
template <int N>
WatchedRun<N> run_watched(const SceneOf<N>& scene, DeviceOf<N>& device, const std::string& file,
                          const RunSettings& settings, bool show_status,
                          std::initializer_list<TickObserverOf<N>*> observers) {
  LiveStatusOf<N> status;
  ObserverListOf<N> all;
  all.add(&status);
  for (TickObserverOf<N>* observer : observers) all.add(observer);
  SceneExchangeOf<N> exchange;
  RunOptions options = settings.options;
  // The live view (--ui): its tap sees every tick, its changes go through the reload
  // watcher (which then runs even with --no-reload, watching no file).
  LoopMonitor monitor;
  std::unique_ptr<LiveViewOf<N>> view;
  if (settings.ui) {
    view = std::make_unique<LiveViewOf<N>>(*settings.ui, file, scene);
    all.add(view->tap());
    options.monitor = &monitor;
  }
  if (settings.reload || view) set_reload_exchange<N>(&options, &exchange);
  WatchedRun<N> run;
  {
    StatusLine<N> line(status, scene.period_s, show_status, view.get());
    std::unique_ptr<ReloadWatcherOf<N>> watcher;
    if (settings.reload || view) {
      ReloadWatcherOptionsOf<N> watch;
      watch.before_destroy = [&status](LoadedSceneOf<N>& retired) { status.drain_retired(retired); };
      watch.watch_files = settings.reload;
      LiveViewOf<N>* shown = view.get();
      watcher = std::make_unique<ReloadWatcherOf<N>>(
          file, scene, &exchange,
          [show_status, shown](const std::string& message) {
            std::fprintf(stderr, "%s%s\n", show_status ? "\r\033[K" : "", printable(message).c_str());
            if (shown != nullptr) shown->add_log(message);
          },
          std::move(watch));
    }
    if (view) {
      view->start(watcher.get(), &monitor, &device);
      if (!settings.ui->loopback) {
        std::fprintf(stderr, "warning: the live view listens on %s, not on loopback: anyone who can reach it "
                             "and has the token can change the forces\n", printable(settings.ui->host).c_str());
      }
      std::fprintf(stderr, "live view: %s\n", view->url().c_str());
      std::fflush(stderr);
    }
    run.summary = run_scene(scene, device, options, &all);
    if (view) {
      view->stop();  // before the watcher goes
      run.live_view = true;
      run.live_events = view->events_sent();
      run.live_dropped_events = view->dropped_events();
      run.live_dropped_ticks = view->dropped_ticks();
    }
    if (watcher) run.replaced_script_faults = watcher->replaced_script_faults();
  }
  std::vector<std::string> log_lines;
  status.drain_log(&log_lines);
  for (const std::string& line : log_lines) std::fprintf(stderr, "%s\n", printable(line).c_str());
  run.reloads = exchange.swaps();
  return run;
}

// A script disabled by a fault (in the version running at the end, or in one a reload
// replaced) is a fault the run saw: the run exits 1.
template <int N>
bool script_faulted(const WatchedRun<N>& run) {
  if (run.replaced_script_faults > 0) return true;
  for (const ScriptReport& script : run.summary.scripts) {
    if (script.disabled) return true;
  }
  return false;
}

// The one rule, for every N, in the CLI and in Python: a run fails (exit 1) when it saw a
// sustained overrun, a non-finite force (zeroed by safety), a device fault, or a script
// disabled by a fault.
template <int N>
bool run_faulted(const WatchedRun<N>& run, const DeviceStatus& device) {
  const RunSummaryOf<N>& summary = run.summary;
  return summary.overrun_fault || summary.safety.nonfinite_faults > 0 || device.fault_seen() || script_faulted(run);
}

// Ends `hapscene run` with 1 when `failed` (else 0). A reload load, or a live view's load
// or validate run, that never finished may still hold a thread: then the process ends at
// once, without running static destructors under it, after flushing its output.
inline int end_run(bool failed) {
  if (ReloadWatcher::abandoned_loads() > 0 || abandoned_live_view_jobs() > 0) {
    const bool output_ok = report_stdout_failure();
    std::fflush(stderr);
    std::_Exit(failed || !output_ok ? kExitFailure : kExitOk);
  }
  return failed ? kExitFailure : kExitOk;
}

}  // namespace hapscene
