#pragma once
// The Haply board's stock firmware has no timeout: the last torque it was sent stays on
// if the host stops sending. hapscene sends zero torque on every way a run ends that it
// controls (the end, Ctrl-C, SIGTERM, a fault, an exception: HaplyDevice's destructor);
// this watchdog covers the ways it does not control. It is a small child process, forked
// when the device opens, that holds the port open and writes a zero-torque frame to it
//   - when this process dies without saying goodbye (a crash, kill -9): the pipe it holds
//     to this process reports a hang-up;
//   - when this process stops ticking for `stall_ns` while a torque is on (hung, stopped
//     by SIGSTOP or a debugger): the heartbeat in shared memory stops moving. The next
//     beat then reports that the watchdog fired (the loop ramps force in again).
// It ignores SIGINT, SIGTERM and SIGHUP (a Ctrl-C reaches the whole process group; the
// parent handles it and says goodbye) and exits when its parent is gone. Between fork and
// exit the child makes only async-signal-safe calls, so forking a threaded process is safe.
#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <string>

#include "engine/devices/haply/haply_protocol.hpp"

namespace hapscene {

class ZeroTorqueWatchdog {
 public:
  // Forks the watchdog; throws std::runtime_error when it cannot (fork, pipe or mmap).
  ZeroTorqueWatchdog(const std::string& port_path, const HaplyFrame& zero_frame, std::int64_t stall_ns);
  // A clean end: the caller has sent zero torque; the watchdog exits without writing.
  ~ZeroTorqueWatchdog();
  ZeroTorqueWatchdog(const ZeroTorqueWatchdog&) = delete;
  ZeroTorqueWatchdog& operator=(const ZeroTorqueWatchdog&) = delete;

  // Each tick (no system call): alive, and whether the torque just sent is non-zero.
  void beat(bool torque_on) noexcept;
  // True once after the watchdog zeroed the torque of a stalled process.
  bool take_fired() noexcept;
  std::uint64_t fired() const noexcept;
  pid_t pid() const noexcept { return pid_; }

  // What parent and child share (in memory mapped before the fork).
  struct Shared {
    std::atomic<std::uint64_t> beats{0};
    std::atomic<std::uint32_t> torque_on{0};
    std::atomic<std::uint32_t> goodbye{0};
    std::atomic<std::uint64_t> fired{0};
  };

 private:
  Shared* shared_{};
  int pipe_write_fd_{-1};
  pid_t pid_{-1};
  std::uint64_t fired_seen_{0};
};

}  // namespace hapscene
