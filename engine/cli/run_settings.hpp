#pragma once
// `hapscene run`: its settings, and the telemetry log of a run whatever its axes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/hapkit_plant.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/run/runner.hpp"
#include "engine/run/telemetry_log.hpp"
#include "engine/serve/ui_address.hpp"

namespace hapscene {

struct RunSettings {
  std::string device{"sim"};
  LinkOptions link;
  RunOptions options;
  SimulationConfig simulation;
  double noise_counts{-1.0};  // < 0: the profile's
  bool quiet{false};
  bool reload{true};          // watch the files and hot-reload them
  std::optional<std::string> log_path;   // --log FILE.csv: per-tick telemetry
  std::optional<std::string> plot_path;  // --plot FILE.svg: the run's time series
  // As given: their meaning depends on the scene's axes (--hold X or --hold X,Y).
  std::optional<std::string> hand_text;
  std::optional<std::string> hold_text;
  std::optional<std::string> start_text;
  std::optional<UiAddress> ui;  // --ui [PORT|HOST:PORT]: the live view (engine/serve)
};

// The --log file's writer for a run of `rate_hz` (null without --log). In simulated time
// the loop outruns any disk: the ring holds the whole run (up to 2^21 samples) so nothing
// is dropped; in real time 2^16 samples (65 s at 1 kHz).
template <int N>
std::unique_ptr<TelemetryLogOf<N>> open_telemetry_log(const RunSettings& settings, double rate_hz) {
  if (!settings.log_path) return nullptr;
  const auto ticks = static_cast<std::size_t>(std::llround(settings.options.duration_s * rate_hz));
  const std::size_t capacity = settings.options.pacing == Pacing::simulated_time
                                   ? std::clamp<std::size_t>(ticks + 1, kDefaultTelemetryCapacity, 1u << 21)
                                   : kDefaultTelemetryCapacity;
  return std::make_unique<TelemetryLogOf<N>>(*settings.log_path, capacity);
}

// Finishes the log and prints its summary line. Returns false when a write failed: never
// claim samples reached a file that refused them (the run then exits 1).
template <int N>
bool finish_telemetry_log(TelemetryLogOf<N>& log, const std::string& path) {
  log.finish();
  if (!log.error().empty()) {
    print_out("  telemetry        FAILED: %s\n", printable(log.error()).c_str());
    std::fprintf(stderr, "hapscene run: %s\n", printable(log.error()).c_str());
    return false;
  }
  print_out("  telemetry        %llu samples written to %s, %llu dropped (ring full)\n",
            static_cast<unsigned long long>(log.written()), printable(path).c_str(),
            static_cast<unsigned long long>(log.dropped()));
  return true;
}

}  // namespace hapscene
