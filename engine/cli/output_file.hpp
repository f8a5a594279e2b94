#pragma once
// Writing a whole output file (report, figure). A path that cannot be opened is invalid
// input (InputError, exit code 2); a write, flush or close that fails afterwards (a full
// disk, /dev/full) is a failure of the command (std::runtime_error, exit code 1). Both
// name the file.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "engine/core/errors.hpp"

namespace hapscene {

// "PATH: write failed: No space left on device".
inline std::string write_failed_message(const std::string& path, int error_number) {
  return path + ": write failed: " + (error_number != 0 ? std::strerror(error_number) : "unknown error");
}

inline void write_output_file(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) throw InputError(path + ": cannot write file");
  errno = 0;
  const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  const int write_errno = errno;
  const bool flushed = written && std::fflush(file) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!written || !flushed || !closed) {
    throw std::runtime_error(write_failed_message(path, !written ? write_errno : !flushed ? flush_errno : errno));
  }
}

}  // namespace hapscene
