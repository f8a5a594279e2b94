#include "engine/devices/haply/zero_torque_watchdog.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace hapscene {
namespace {

std::int64_t now_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

void sleep_ms(long ms) noexcept {
  timespec t{0, ms * 1'000'000};
  while (nanosleep(&t, &t) != 0 && errno == EINTR) {
  }
}

// Writes the frame whole to the port, opening it again when the held descriptor fails
// (the device was re-plugged); tries for about a second. Async-signal-safe.
void write_zero(const char* path, int* fd, const std::uint8_t* frame, std::size_t size) noexcept {
  for (int attempt = 0; attempt < 100; ++attempt) {
    if (*fd < 0) *fd = open(path, O_WRONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (*fd >= 0) {
      const ssize_t n = write(*fd, frame, size);
      if (n == static_cast<ssize_t>(size)) return;
      if (n < 0 && errno != EAGAIN && errno != EINTR) {
        close(*fd);
        *fd = -1;
      }
    }
    sleep_ms(10);
  }
}

[[noreturn]] void run_watchdog(ZeroTorqueWatchdog::Shared* shared, int pipe_read_fd, const char* path,
                               const std::uint8_t* frame, std::size_t size, std::int64_t stall_ns) noexcept {
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGINT, &ignore, nullptr);
  sigaction(SIGTERM, &ignore, nullptr);
  sigaction(SIGHUP, &ignore, nullptr);
  sigaction(SIGPIPE, &ignore, nullptr);
  prctl(PR_SET_NAME, "hapscene-zero", 0, 0, 0);
  // Nothing of the parent's stays open here (its pipes to a caller would not see their end).
  for (int other = 0; other < 1024; ++other) {
    if (other != pipe_read_fd) close(other);
  }
  int fd = open(path, O_WRONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);  // hold the port

  std::uint64_t last_beats = shared->beats.load(std::memory_order_relaxed);
  std::int64_t last_change_ns = now_ns();
  bool zeroed_this_stall = false;
  for (;;) {
    pollfd parent{pipe_read_fd, POLLIN, 0};
    const int ready = poll(&parent, 1, 5);
    if (ready > 0) {
      // The pipe's write end closed: the parent ended, cleanly (goodbye) or not.
      char byte = 0;
      const ssize_t n = read(pipe_read_fd, &byte, 1);
      if (n <= 0 || (parent.revents & POLLHUP) != 0) {
        if (shared->goodbye.load(std::memory_order_acquire) == 0) write_zero(path, &fd, frame, size);
        _exit(0);
      }
    }
    const std::uint64_t beats = shared->beats.load(std::memory_order_relaxed);
    const std::int64_t t_ns = now_ns();
    if (beats != last_beats) {
      last_beats = beats;
      last_change_ns = t_ns;
      zeroed_this_stall = false;
    } else if (!zeroed_this_stall && shared->torque_on.load(std::memory_order_relaxed) != 0 &&
               t_ns - last_change_ns > stall_ns) {
      write_zero(path, &fd, frame, size);
      zeroed_this_stall = true;
      shared->fired.fetch_add(1, std::memory_order_release);
    }
  }
}

}  // namespace

ZeroTorqueWatchdog::ZeroTorqueWatchdog(const std::string& port_path, const HaplyFrame& zero_frame,
                                       std::int64_t stall_ns) {
  void* memory = mmap(nullptr, sizeof(Shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED) throw std::runtime_error(std::string("zero-torque watchdog: mmap: ") + std::strerror(errno));
  shared_ = new (memory) Shared();
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    munmap(memory, sizeof(Shared));
    throw std::runtime_error(std::string("zero-torque watchdog: pipe: ") + std::strerror(errno));
  }
  // Everything the child touches is made before the fork.
  const std::string path = port_path;
  const HaplyFrame frame = zero_frame;
  pid_ = fork();
  if (pid_ < 0) {
    const int error = errno;
    close(fds[0]);
    close(fds[1]);
    munmap(memory, sizeof(Shared));
    throw std::runtime_error(std::string("zero-torque watchdog: fork: ") + std::strerror(error));
  }
  if (pid_ == 0) {
    close(fds[1]);
    run_watchdog(shared_, fds[0], path.c_str(), frame.bytes.data(), frame.size, stall_ns);
  }
  close(fds[0]);
  pipe_write_fd_ = fds[1];
}

ZeroTorqueWatchdog::~ZeroTorqueWatchdog() {
  shared_->goodbye.store(1, std::memory_order_release);
  close(pipe_write_fd_);
  // The child exits at once on the hang-up; reap it so no zombie is left.
  for (int i = 0; i < 200; ++i) {
    const pid_t done = waitpid(pid_, nullptr, WNOHANG);
    if (done == pid_ || done < 0) break;
    sleep_ms(1);
  }
  munmap(shared_, sizeof(Shared));
}

void ZeroTorqueWatchdog::beat(bool torque_on) noexcept {
  shared_->torque_on.store(torque_on ? 1 : 0, std::memory_order_relaxed);
  shared_->beats.fetch_add(1, std::memory_order_relaxed);
}

bool ZeroTorqueWatchdog::take_fired() noexcept {
  const std::uint64_t fired = shared_->fired.load(std::memory_order_acquire);
  if (fired == fired_seen_) return false;
  fired_seen_ = fired;
  return true;
}

std::uint64_t ZeroTorqueWatchdog::fired() const noexcept { return shared_->fired.load(std::memory_order_acquire); }

}  // namespace hapscene
