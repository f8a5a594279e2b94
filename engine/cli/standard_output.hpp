#pragma once
// Writing to standard output with every failure kept. A write that fails inside stdio
// (a full disk, /dev/full, a closed pipe) only sets the stream's error flag, and errno
// is overwritten by whatever runs next, so each write of the commands goes through
// these functions, which keep the first failure's errno. main() then reports it
// ("standard output: write failed: No space left on device") and exits 1.
#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>

namespace hapscene {

// The first write error of standard output: an errno value, -1 when stdio did not say
// why, 0 while none.
inline int& stdout_error() {
  static int error_number = 0;
  return error_number;
}

inline void note_stdout_failure(int error_number) {
  if (stdout_error() == 0) stdout_error() = error_number != 0 ? error_number : -1;
}

// printf to standard output.
[[gnu::format(printf, 1, 2)]] inline void print_out(const char* pattern, ...) {
  std::va_list values;
  va_start(values, pattern);
  errno = 0;
  const int written = std::vprintf(pattern, values);
  const int error_number = errno;
  va_end(values);
  if (written < 0) note_stdout_failure(error_number);
}

inline void write_out(const std::string& text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size()) note_stdout_failure(errno);
}

// Flushes standard output; false when anything written so far failed to arrive.
inline bool flush_out() {
  errno = 0;
  if (std::fflush(stdout) != 0) note_stdout_failure(errno);
  if (std::ferror(stdout) != 0) note_stdout_failure(0);
  return stdout_error() == 0;
}

// Flushes standard output; when anything failed to arrive, says why on stderr
// ("hapscene: standard output: write failed: No space left on device") and returns false.
inline bool report_stdout_failure() {
  if (flush_out()) return true;
  const int error_number = stdout_error();
  std::fprintf(stderr, "hapscene: standard output: write failed: %s\n",
               error_number > 0 ? std::strerror(error_number) : "the system gave no reason");
  return false;
}

}  // namespace hapscene
