#include "engine/run/telemetry_log.hpp"

#include <charconv>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

void append_number(double value, std::string* out) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out->append(buffer, ec == std::errc() ? end : buffer);
}

}  // namespace

std::string telemetry_csv_line(const TelemetrySample& s) {
  std::string line;
  for (const double value : {s.t_s, s.x_m, s.v_m_per_s, s.force_N, s.output_N, s.duty}) {
    append_number(value + 0.0, &line);  // + 0.0: no "-0"
    line += ',';
  }
  line += s.direction_high ? "1\n" : "0\n";
  return line;
}

TelemetryLog::TelemetryLog(const std::string& path, std::size_t capacity) : ring_(capacity), path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) throw InputError(path + ": cannot write file");
  errno = 0;
  if (std::fputs(kTelemetryCsvHeader, file_) < 0 || std::fputc('\n', file_) == EOF) note_write_error(errno);
  writer_ = std::thread([this] { drain_loop(); });
}

void TelemetryLog::note_write_error(int error_number) {
  if (error_.empty()) {
    error_ = path_ + ": write failed: " + (error_number != 0 ? std::strerror(error_number) : "unknown error");
  }
}

TelemetryLog::~TelemetryLog() { finish(); }

void TelemetryLog::on_tick(const TickState& state) noexcept {
  const TelemetrySample sample{state.t_s,      state.x_m,          state.v_m_per_s,
                               state.effects_force_N, state.output_N, state.command.duty,
                               state.command.direction_high};
  if (!ring_.try_push(sample)) dropped_.fetch_add(1, std::memory_order_relaxed);
}

// Drain whatever is there, then nap briefly; after stop, drain the rest and return.
void TelemetryLog::drain_loop() {
  TelemetrySample sample;
  for (;;) {
    const bool stopping = stop_.load(std::memory_order_acquire);
    bool any = false;
    while (ring_.try_pop(&sample)) {
      // After a failed write the rest is drained and discarded, so the loop never waits.
      if (!error_.empty()) continue;
      const std::string line = telemetry_csv_line(sample);
      errno = 0;
      if (std::fwrite(line.data(), 1, line.size(), file_) != line.size()) {
        note_write_error(errno);
        continue;
      }
      written_.fetch_add(1, std::memory_order_relaxed);
      any = true;
    }
    if (stopping) return;
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void TelemetryLog::finish() {
  if (writer_.joinable()) {
    stop_.store(true, std::memory_order_release);
    writer_.join();
  }
  if (file_ != nullptr) {
    // Buffered lines reach the disk here: a full disk often shows only now.
    errno = 0;
    if (std::fflush(file_) != 0) note_write_error(errno);
    errno = 0;
    if (std::fclose(file_) != 0) note_write_error(errno);
    file_ = nullptr;
  }
}

}  // namespace hapscene
