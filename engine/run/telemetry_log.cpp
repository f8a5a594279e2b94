#include "engine/run/telemetry_log.hpp"

#include <charconv>
#include <cerrno>
#include <chrono>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

void append_number(double value, std::string* out) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out->append(buffer, ec == std::errc() ? end : buffer);
}

// Each axis's value, then a comma.
template <int N>
void append_axes(const Axes<N>& value, std::string* out) {
  for (int i = 0; i < N; ++i) {
    append_number(component(value, i) + 0.0, out);  // + 0.0: no "-0"
    *out += ',';
  }
}

// Each motor's duty and direction, separated by commas.
template <int N>
void append_command(const typename SceneParts<N>::Command& command, std::string* out) {
  for (int i = 0; i < N; ++i) {
    const MotorCommand& motor = motor_of(command, i);
    if (i > 0) *out += ',';
    append_axes<1>(motor.duty, out);
    *out += motor.direction_high ? '1' : '0';
  }
}

}  // namespace

template <int N>
std::string telemetry_csv_line(const TelemetrySampleOf<N>& s) {
  std::string line;
  append_axes<1>(s.t_s, &line);
  for (const Axes<N>& value : {s.x_m, s.v_m_per_s, s.force_N, s.output_N}) append_axes<N>(value, &line);
  append_command<N>(s.command, &line);
  line += '\n';
  return line;
}

namespace {

// The log's file, created or emptied, never through a symbolic link planted at its path
// (O_NOFOLLOW) and never a pipe or a folder (opened without waiting for a reader, then
// checked): a regular file, or a device such as /dev/null.
std::FILE* open_log_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    if (error == ELOOP) throw InputError(path + ": is a symbolic link; the log is not written through one");
    if (error == ENXIO) throw InputError(path + ": not a regular file; the log is written to files only");  // a pipe
    throw InputError(path + ": cannot write file (" + std::strerror(error) + ")");
  }
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !(S_ISREG(status.st_mode) || S_ISCHR(status.st_mode))) {
    ::close(fd);
    throw InputError(path + ": not a regular file; the log is written to files only");
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::FILE* file = ::fdopen(fd, "wb");
  if (file == nullptr) {
    ::close(fd);
    throw InputError(path + ": cannot write file");
  }
  return file;
}

}  // namespace

template <int N>
TelemetryLogOf<N>::TelemetryLogOf(const std::string& path, std::size_t capacity) : ring_(capacity), path_(path) {
  file_ = open_log_file(path);
  errno = 0;
  if (std::fputs(csv_header_line(telemetry_columns<N>()).c_str(), file_) < 0 || std::fputc('\n', file_) == EOF) note_write_error(errno);
  writer_ = std::thread([this] { drain_loop(); });
}

template <int N>
void TelemetryLogOf<N>::note_write_error(int error_number) {
  if (error_.empty()) {
    error_ = path_ + ": write failed: " + (error_number != 0 ? std::strerror(error_number) : "unknown error");
  }
}

template <int N>
TelemetryLogOf<N>::~TelemetryLogOf() { finish(); }

template <int N>
void TelemetryLogOf<N>::on_tick(const TickStateOf<N>& state) noexcept {
  if (!ring_.try_push(telemetry_sample(state))) dropped_.fetch_add(1, std::memory_order_relaxed);
}

// Drain whatever is there, then nap briefly; after stop, drain the rest and return.
template <int N>
void TelemetryLogOf<N>::drain_loop() {
  TelemetrySampleOf<N> sample;
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

template <int N>
void TelemetryLogOf<N>::finish() {
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

// The axis counts scenes are compiled for.
#define HAPSCENE_TELEMETRY_LOG(N)                                               \
  template std::string telemetry_csv_line<N>(const TelemetrySampleOf<N>&); \
  template class TelemetryLogOf<N>;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_TELEMETRY_LOG)
#undef HAPSCENE_TELEMETRY_LOG

}  // namespace hapscene
