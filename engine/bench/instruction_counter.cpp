#include "engine/bench/instruction_counter.hpp"

#include <cerrno>
#include <cstring>

#if defined(__linux__)
#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace hapscene {

InstructionCounter::InstructionCounter() {
#if defined(__linux__)
  // One hardware counter: user-space instructions of this thread, disabled until start().
  perf_event_attr attr{};
  attr.type = PERF_TYPE_HARDWARE;
  attr.size = sizeof attr;
  attr.config = PERF_COUNT_HW_INSTRUCTIONS;
  attr.disabled = 1;
  attr.exclude_kernel = 1;
  attr.exclude_hv = 1;
  const long fd = syscall(SYS_perf_event_open, &attr, 0, -1, -1, 0);
  if (fd < 0) {
    reason_ = std::string("perf_event_open: ") + std::strerror(errno);
    return;
  }
  fd_ = static_cast<int>(fd);
#else
  reason_ = "performance counters are only read on Linux";
#endif
}

InstructionCounter::~InstructionCounter() {
#if defined(__linux__)
  if (fd_ >= 0) close(fd_);
#endif
}

void InstructionCounter::start() noexcept {
#if defined(__linux__)
  if (fd_ < 0) return;
  ioctl(fd_, PERF_EVENT_IOC_RESET, 0);
  ioctl(fd_, PERF_EVENT_IOC_ENABLE, 0);
#endif
}

std::uint64_t InstructionCounter::stop() noexcept {
#if defined(__linux__)
  if (fd_ < 0) return 0;
  ioctl(fd_, PERF_EVENT_IOC_DISABLE, 0);
  std::uint64_t count = 0;
  if (read(fd_, &count, sizeof count) != static_cast<ssize_t>(sizeof count)) return 0;
  return count;
#else
  return 0;
#endif
}

}  // namespace hapscene
