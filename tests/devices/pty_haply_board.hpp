#pragma once
// A fake board running Haply's stock firmware (fake_haply_board.hpp) on the master side of a
// pseudo-terminal, answering in its own thread: the device (or a hapscene process) opens
// the slave as it would open /dev/ttyACM0.
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <doctest/doctest.h>

#include "tests/devices/fake_haply_board.hpp"

namespace hapscene::test {

// The board's side of the pseudo-terminal, answering in its own thread.
class PtyHaplyBoard {
 public:
  PtyHaplyBoard() {
    master_ = posix_openpt(O_RDWR | O_NOCTTY);
    REQUIRE(master_ >= 0);
    REQUIRE(grantpt(master_) == 0);
    REQUIRE(unlockpt(master_) == 0);
    path_ = ptsname(master_);
    thread_ = std::thread([this] { serve(); });
  }
  ~PtyHaplyBoard() {
    stop_.store(true);
    thread_.join();
    close(master_);
  }

  const std::string& path() const { return path_; }

  // A copy of the board's state, or a change to it, under the lock.
  template <typename F>
  auto with_board(F f) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return f(board_);
  }
  // Polls (every ms, up to `timeout_ms`) until `ready(board)` holds.
  template <typename F>
  bool wait_for(F ready, int timeout_ms) {
    for (int i = 0; i < timeout_ms; ++i) {
      if (with_board(ready)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return with_board(ready);
  }

 private:
  void serve() {
    std::vector<std::uint8_t> out;
    std::uint8_t buffer[256];
    while (!stop_.load()) {
      pollfd fd{master_, POLLIN, 0};
      if (poll(&fd, 1, 1) <= 0) continue;
      const ssize_t n = read(master_, buffer, sizeof buffer);
      if (n <= 0) continue;
      out.clear();
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        board_.receive(buffer, static_cast<std::size_t>(n), &out);
      }
      if (!out.empty()) (void)!write(master_, out.data(), out.size());
    }
  }

  int master_{-1};
  std::string path_;
  std::mutex mutex_;
  FakeHaplyBoard board_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};


}  // namespace hapscene::test
