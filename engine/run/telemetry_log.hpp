#pragma once
// `hapscene run --log FILE.csv`: per-tick telemetry written without ever blocking the
// loop. The loop pushes one sample per tick into an SpscRing allocated before the run; a
// writer thread drains it into the file. A full ring drops the sample and counts it.
//
// CSV columns (the header line, exactly):
//   t_s,x_m,v_m_per_s,force_N,output_N,duty,direction
// t_s tick time since the start; x_m measured handle position; v_m_per_s estimated
// velocity (0 when the scene needs none); force_N what the effects asked for; output_N
// what the device was commanded after safety; duty the PWM duty in [0, 1]; direction the
// direction pin (1 high, 0 low). Numbers in their shortest exact form.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>

#include "engine/run/runner.hpp"
#include "engine/run/telemetry_ring.hpp"

namespace hapscene {

inline constexpr const char* kTelemetryCsvHeader = "t_s,x_m,v_m_per_s,force_N,output_N,duty,direction";
inline constexpr std::size_t kDefaultTelemetryCapacity = 1u << 16;  // 65 s at 1 kHz

struct TelemetrySample {
  double t_s{};
  double x_m{};
  double v_m_per_s{};
  double force_N{};
  double output_N{};
  double duty{};
  bool direction_high{};
};

// One CSV line (with the newline) for a sample.
std::string telemetry_csv_line(const TelemetrySample& sample);

class TelemetryLog final : public TickObserver {
 public:
  // Opens the file (InputError when it cannot) and starts the writer thread.
  TelemetryLog(const std::string& path, std::size_t capacity = kDefaultTelemetryCapacity);
  ~TelemetryLog() override;

  // The loop's side: push, or count a drop. Never blocks, never allocates.
  void on_tick(const TickState& state) noexcept override;

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

  SpscRing<TelemetrySample> ring_;
  std::string path_;
  std::FILE* file_{nullptr};
  std::string error_;  // written by the writer thread until joined, then by finish()
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> written_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::thread writer_;
};

}  // namespace hapscene
