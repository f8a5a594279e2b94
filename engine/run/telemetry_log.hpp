#pragma once
// `hapscene run --log FILE.csv`: per-tick telemetry written without ever blocking the
// loop. The loop pushes one sample per tick into an SpscRing allocated before the run; a
// writer thread drains it into the file. A full ring drops the sample and counts it.
//
// CSV columns (the header line, exactly; telemetry_columns below writes it):
//   t_s,x_m,v_m_per_s,force_N,output_N,duty,direction
// t_s tick time since the start; x_m measured handle position; v_m_per_s estimated
// velocity (0 when the scene needs none); force_N what the effects asked for; output_N
// what the device was commanded after safety; duty the PWM duty in [0, 1]; direction the
// direction pin (1 high, 0 low). Numbers in their shortest exact form.
// A 2-DOF scene's log has a column per axis and per motor (the header line, exactly):
//   t_s,x_m,y_m,vx_m_per_s,vy_m_per_s,force_x_N,force_y_N,output_x_N,output_y_N,duty_1,direction_1,duty_2,direction_2
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "engine/base/axis_columns.hpp"
#include "engine/run/runner.hpp"
#include "engine/run/telemetry_ring.hpp"

namespace hapscene {

// The log's columns for N axes: t_s, the handle's state (axis_columns.hpp), then each
// motor's duty and direction (one motor per axis). The header line is these, joined.
template <int N>
std::vector<std::string> telemetry_columns() {
  std::vector<std::string> columns{"t_s"};
  for (std::string& column : handle_state_columns<N>()) columns.push_back(std::move(column));
  for (int motor = 0; motor < N; ++motor) {
    columns.push_back(motor_column<N>("duty", motor));
    columns.push_back(motor_column<N>("direction", motor));
  }
  return columns;
}
inline constexpr std::size_t kDefaultTelemetryCapacity = 1u << 16;  // 65 s at 1 kHz

// One tick of a scene with N axes.
template <int N>
struct TelemetrySampleOf {
  double t_s{};
  Axes<N> x_m{};
  Axes<N> v_m_per_s{};
  Axes<N> force_N{};
  Axes<N> output_N{};
  typename SceneParts<N>::Command command{};  // per motor: duty and direction
};

using TelemetrySample = TelemetrySampleOf<1>;

// The sample of one tick: what the log writes, and what in-memory recordings keep (the
// Python module's simulate()), so both hold the same values.
template <int N>
TelemetrySampleOf<N> telemetry_sample(const TickStateOf<N>& state) noexcept {
  return {state.t_s, state.x_m, state.v_m_per_s, state.effects_force_N, state.output_N, state.command};
}

// One CSV line (with the newline) for a sample.
template <int N>
std::string telemetry_csv_line(const TelemetrySampleOf<N>& sample);

template <int N>
class TelemetryLogOf final : public TickObserverOf<N> {
 public:
  // Opens the file (InputError when it cannot) and starts the writer thread.
  TelemetryLogOf(const std::string& path, std::size_t capacity = kDefaultTelemetryCapacity);
  ~TelemetryLogOf() override;

  // The loop's side: push, or count a drop. Never blocks, never allocates.
  void on_tick(const TickStateOf<N>& state) noexcept override;

  // Stops the writer after it has drained the ring, flushes and closes the file.
  // Idempotent. A write, flush or close that failed is kept for error().
  void finish();

  // Empty while every line reached the file; else "PATH: write failed: <reason>" (the
  // first failure; later samples are not written, and written() stops counting).
  const std::string& error() const noexcept { return error_; }

  std::uint64_t written() const noexcept { return written_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  void drain_loop();
  void note_write_error(int error_number);

  SpscRing<TelemetrySampleOf<N>> ring_;
  std::string path_;
  std::FILE* file_{nullptr};
  std::string error_;  // written by the writer thread until joined, then by finish()
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> written_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::thread writer_;
};

using TelemetryLog = TelemetryLogOf<1>;

}  // namespace hapscene
