#include "engine/bench/soak.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/harness/force_field.hpp"
#include "engine/load/validate_thresholds.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {
namespace {

// Streams every tick into per-window sums; allocates nothing while the run goes.
class SoakWatch final : public TickObserver {
 public:
  SoakWatch(const SimulatedHapkit& device, const ForceField& field, double mass_kg, std::uint64_t window_ticks)
      : device_(device), field_(field), mass_kg_(mass_kg), window_ticks_(window_ticks) {}

  void on_start(const TickState& s) override { lua_bytes_start = lua_bytes(s); }
  void on_finish(const TickState& s) override {
    lua_bytes_end = lua_bytes(s);
    for (const auto& script : s.scripts) {
      if (script->disabled()) result.script_faults.emplace_back(script->fault_message());
    }
  }

  void on_tick(const TickState& s) noexcept override {
    const double x = device_.x_m();
    const double v = device_.v_m_per_s();
    if (!std::isfinite(x) || !std::isfinite(v) || !std::isfinite(s.output_N) || !std::isfinite(s.command.duty)) {
      ++result.nonfinite_ticks;
      return;
    }
    sum_x_ += x;
    sum_e_ += 0.5 * mass_kg_ * v * v + field_.potential_at_J(x);
    if (++in_window_ < window_ticks_) return;
    // A window is complete: its means (the first, start-up, window is not judged).
    const double mean_x = sum_x_ / static_cast<double>(in_window_);
    const double mean_e = sum_e_ / static_cast<double>(in_window_);
    if (window_index_++ > 0) {
      if (result.windows == 0) first_x_ = mean_x, low_x_ = high_x_ = mean_x, low_e_ = high_e_ = mean_e;
      low_x_ = std::min(low_x_, mean_x), high_x_ = std::max(high_x_, mean_x);
      low_e_ = std::min(low_e_, mean_e), high_e_ = std::max(high_e_, mean_e);
      last_x_ = mean_x;
      ++result.windows;
    }
    sum_x_ = sum_e_ = 0.0;
    in_window_ = 0;
  }

  void finish() {
    if (result.windows == 0) return;
    result.position_spread_m = high_x_ - low_x_;
    result.energy_spread_J = high_e_ - low_e_;
    result.first_last_position_m = last_x_ - first_x_;
  }

  SoakResult result;
  std::size_t lua_bytes_start{};
  std::size_t lua_bytes_end{};

 private:
  static std::size_t lua_bytes(const TickState& s) {
    std::size_t bytes = 0;
    for (const auto& script : s.scripts) bytes += script->memory_bytes();
    return bytes;
  }

  const SimulatedHapkit& device_;
  const ForceField& field_;
  double mass_kg_;
  std::uint64_t window_ticks_;
  std::uint64_t in_window_{};
  std::uint64_t window_index_{};
  double sum_x_{}, sum_e_{};
  double first_x_{}, last_x_{};
  double low_x_{}, high_x_{}, low_e_{}, high_e_{};
};

}  // namespace

long resident_kB() {
  std::FILE* file = std::fopen("/proc/self/statm", "r");
  if (file == nullptr) return 0;
  long size_pages = 0, resident_pages = 0;
  const int read = std::fscanf(file, "%ld %ld", &size_pages, &resident_pages);
  std::fclose(file);
  return read == 2 ? resident_pages * 4 : 0;  // 4 kB pages
}

SoakResult run_soak(const Scene& scene, std::uint64_t ticks) {
  // The sweeping hand: -40 .. +40 mm at 80 mm/s, a period of 2 s.
  SimulationConfig config;
  config.hand.motion = HandMotion::sweep;
  SimulatedHapkit device(scene.device, config);
  const double period_s = 2.0 * (config.hand.sweep_max_m - config.hand.sweep_min_m) / config.hand.speed_m_per_s;
  // Only the field's potential is read (its stiff regions are not), so the default
  // threshold serves every environment.
  const ForceField field = probe_force_field(scene, ValidateThresholds{}.stiff_threshold_N_per_m);
  SoakWatch watch(device, field, scene.device.plant.mass_kg,
                  static_cast<std::uint64_t>(std::llround(period_s * scene.rate_hz)));

  const long rss_start_kB = resident_kB();
  const auto begin = std::chrono::steady_clock::now();
  const RunOptions options{.duration_s = static_cast<double>(ticks) * scene.period_s, .pacing = Pacing::simulated_time};
  const RunSummary summary = run_scene(scene, device, options, &watch);
  watch.finish();
  SoakResult result = watch.result;
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  result.ticks = summary.ticks;
  result.rss_start_kB = rss_start_kB;
  result.rss_end_kB = resident_kB();
  result.lua_bytes_start = watch.lua_bytes_start;
  result.lua_bytes_end = watch.lua_bytes_end;
  result.safety = summary.safety;
  result.script_errors = summary.script_errors + summary.script_budget_overruns;
  return result;
}

}  // namespace hapscene
