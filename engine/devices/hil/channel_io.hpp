#pragma once
// Whole messages over the board channel (a stream socket), for both ends: the host
// (SimulatedBoard) and the board process (hapscene-board, which is built from its own
// folder without the engine library, hence header-only).
//
// A reply arrives within tens of microseconds during a run, so the host's read spins on
// non-blocking receives first, which spares two context switches per round trip when the
// board process runs on the other core, then sleeps in poll until the rest arrives. The
// board process does not spin for the host's next request (spin_reads 0): it comes when the
// wall clock says, and a spinning board takes the core another board needs (two boards
// for a 2-DOF device: 2 s of simulated time took 11.6 s with both spinning, 4.1 s without).
#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>

namespace hapscene::board_channel {

// Non-blocking reads the host tries before sleeping in poll (about 100 us of this VM's
// time; without them 2 s of a 1-DOF board's simulated time took 2.6 s instead of 1.3 s).
inline constexpr int kSpinReads = 200;

// Milliseconds since `start` on the monotonic clock.
inline long elapsed_ms_since(const timespec& start) noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (now.tv_sec - start.tv_sec) * 1000 + (now.tv_nsec - start.tv_nsec) / 1'000'000;
}

// Reads exactly `size` bytes of `fd` into `data`, across short reads and interrupted
// calls, within `timeout_ms` of the call (< 0: no limit). False on a timeout (then
// *timed_out is set, when given), an end of file or an error.
inline bool read_exactly(int fd, void* data, std::size_t size, int timeout_ms, bool* timed_out = nullptr,
                         int spin_reads = kSpinReads) noexcept {
  auto* at = static_cast<std::uint8_t*>(data);
  timespec start{};
  clock_gettime(CLOCK_MONOTONIC, &start);
  for (int spin = 0; spin < spin_reads && size > 0; ++spin) {
    const ssize_t n = recv(fd, at, size, MSG_DONTWAIT);
    if (n == 0) return false;
    if (n > 0) {
      at += n;
      size -= static_cast<std::size_t>(n);
    }
  }
  const auto time_out = [&] {
    if (timed_out != nullptr) *timed_out = true;
    return false;
  };
  while (size > 0) {
    int wait_ms = -1;
    if (timeout_ms >= 0) {
      const long elapsed_ms = elapsed_ms_since(start);
      if (elapsed_ms >= timeout_ms) return time_out();
      wait_ms = static_cast<int>(timeout_ms - elapsed_ms);
    }
    pollfd waiting{fd, POLLIN, 0};
    const int ready = poll(&waiting, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) return time_out();
    if (ready < 0) return false;
    const ssize_t n = read(fd, at, size);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) return false;
    at += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// Writes all `size` bytes of `data` to `fd`, across short writes and interrupted calls.
// False when the other end is gone (never SIGPIPE) or on an error.
inline bool write_exactly(int fd, const void* data, std::size_t size) noexcept {
  const auto* at = static_cast<const std::uint8_t*>(data);
  while (size > 0) {
    const ssize_t n = send(fd, at, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace hapscene::board_channel
