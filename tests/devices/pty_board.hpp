#pragma once
// A FakeBoard on the master side of a pseudo-terminal, answering in its own thread: the
// device under test opens the slave as it would open /dev/ttyACM0. The test steers the
// board through atomics (mute it, stop its STATEs, move it, reset it, send garbage) and
// unplug() closes the master as a pulled cable would.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <climits>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "tests/devices/fake_board.hpp"

namespace hapscene::test {

class PtyBoard {
 public:
  PtyBoard() {
    master_ = posix_openpt(O_RDWR | O_NOCTTY);
    REQUIRE(master_ >= 0);
    REQUIRE(grantpt(master_) == 0);
    REQUIRE(unlockpt(master_) == 0);
    path_ = ptsname(master_);
    thread_ = std::thread([this] { serve(); });
  }
  ~PtyBoard() { unplug(); }
  PtyBoard(const PtyBoard&) = delete;
  PtyBoard& operator=(const PtyBoard&) = delete;

  // Closes the master: the device's next read fails as if the cable were pulled.
  void unplug() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
    if (master_ >= 0) close(master_);
    master_ = -1;
  }

  const std::string& path() const { return path_; }
  std::atomic<bool> muted{false};         // answers nothing
  std::atomic<int> mute_after_commands{-1};  // >= 0: mutes itself once it has taken this many COMMANDs
  std::atomic<bool> states_muted{false};  // answers COMMANDs with STATS: alive, no position
  std::atomic<int> counts{500};           // the board's unwrapped counts
  std::atomic<int> reset_to{INT_MIN};     // != INT_MIN: reset the board, `counts` then this
  std::atomic<int> garbage_bytes{0};      // bytes of noise sent before the next answers
  std::atomic<bool> corrupt{false};       // every answer's last byte (its CRC) flipped
  std::atomic<int> commands{0};
  std::atomic<int> hellos{0};
  std::atomic<int> last_duty{-1};
  std::atomic<int> nonzero_commands{0};   // COMMANDs with a duty above zero
  std::atomic<int> zero_commands{0};      // COMMANDs with zero duty
  std::atomic<int> nonzero_since_reset{0};  // COMMANDs with a duty the board took since its last reset

 private:
  void serve() {
    FakeBoard board;
    std::vector<std::uint8_t> out;
    std::uint8_t buffer[256];
    int seen_commands = 0;
    while (!stop_.load()) {
      pollfd fd{master_, POLLIN, 0};
      if (poll(&fd, 1, 1) <= 0) continue;
      const ssize_t n = read(master_, buffer, sizeof buffer);
      if (n <= 0) continue;
      board.muted = muted.load();
      board.states_muted = states_muted.load();
      const int reset = reset_to.exchange(INT_MIN);
      if (reset != INT_MIN) {
        board.reset(reset);
        counts.store(reset);
        nonzero_since_reset.store(0);
      }
      board.unwrapped_counts = counts.load();
      out.clear();
      for (int garbage = garbage_bytes.exchange(0); garbage > 0; --garbage) {
        out.push_back(static_cast<std::uint8_t>(0x5A ^ garbage));
      }
      board.receive(buffer, static_cast<std::size_t>(n), &out);
      if (corrupt.load() && !out.empty()) out.back() ^= 0xFF;
      if (board.commands != seen_commands) {
        seen_commands = board.commands;
        (board.last_command.duty > 0 ? nonzero_commands : zero_commands).fetch_add(1);
        if (board.last_command.duty > 0) nonzero_since_reset.fetch_add(1);
      }
      commands.store(board.commands);
      const int mute_after = mute_after_commands.load();
      if (mute_after >= 0 && board.commands >= mute_after) muted.store(true);
      hellos.store(board.hellos);
      last_duty.store(board.last_command.duty);
      if (!out.empty()) (void)!write(master_, out.data(), out.size());
    }
  }

  int master_{-1};
  std::string path_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace hapscene::test
