#include "engine/devices/board_handshake.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

#include "engine/base/clock.hpp"
#include "engine/base/format.hpp"
#include "engine/devices/board_report.hpp"

namespace hapscene {

void complete_handshakes(std::span<const BoardToOpen> boards, double timeout_s, int baud) {
  const std::int64_t deadline_ns = monotonic_now_ns() + static_cast<std::int64_t>(timeout_s * 1e9);
  for (;;) {
    bool all_running = true;
    for (const BoardToOpen& board : boards) all_running = all_running && board.link->state() == LinkState::running;
    if (all_running) return;
    const std::int64_t now_ns = monotonic_now_ns();
    if (now_ns > deadline_ns) {
      for (const BoardToOpen& board : boards) {
        if (board.link->state() == LinkState::running) continue;
        throw std::runtime_error(board.name + ": the handshake did not complete within " +
                                 printf_string("%g", timeout_s) + " s: " + handshake_failure(*board.link) +
                                 " (is the hapscene firmware flashed, and the baud rate " + std::to_string(baud) +
                                 "?)");
      }
    }
    for (const BoardToOpen& board : boards) {
      if (board.link->state() == LinkState::running) continue;
      board.link->send(MotorCommand{}, now_ns);
      board.link->poll(now_ns);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace hapscene
