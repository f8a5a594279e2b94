#pragma once
// The serial wire between the host's BoardLink and the simulated board, as a ByteLink,
// with faults a test can inject in either direction: a corrupted byte, dropped bytes,
// injected garbage, or a host that stops sending altogether.
//
// In lock-step the host's bytes go straight into the board's queue. While the board runs
// on a thread of its own (set_paced, PacedWorld), bytes cross in two rings instead: the
// host's thread reads and writes its ends, the world's thread moves them into and out of
// the board at each substep (move_to_board, move_to_host).
#include <cstdint>

#include "engine/devices/byte_link.hpp"
#include "engine/devices/hil/byte_ring.hpp"
#include "engine/devices/hil/simulated_board.hpp"

namespace hapscene {

struct WireFaults {
  std::uint32_t drop_next{};      // drop this many of the next bytes
  std::uint32_t corrupt_in{};     // XOR the byte after this many more with corrupt_mask
  std::uint8_t corrupt_mask{};    // 0: nothing to corrupt

  // Applies the faults to one byte; false when it is dropped.
  bool pass(std::uint8_t* byte) noexcept {
    if (drop_next > 0) {
      --drop_next;
      return false;
    }
    if (corrupt_mask != 0) {
      if (corrupt_in == 0) {
        *byte ^= corrupt_mask;
        corrupt_mask = 0;
      } else {
        --corrupt_in;
      }
    }
    return true;
  }
};

class Wire final : public ByteLink {
 public:
  explicit Wire(SimulatedBoard& board) : board_(board) {}

  long read_some(std::uint8_t* data, std::size_t capacity) noexcept override {
    std::size_t kept = 0;
    // What crossed the ring first (all of it, after a paced run), then the board's queue.
    std::size_t n = 0;
    while (n < capacity && to_host_ring_.pop(&data[n])) ++n;
    if (!paced_) n += board_.take_bytes(data + n, capacity - n);
    for (std::size_t i = 0; i < n; ++i) {
      std::uint8_t byte = data[i];
      if (to_host.pass(&byte)) data[kept++] = byte;
    }
    return static_cast<long>(kept);
  }

  long write_some(const std::uint8_t* data, std::size_t size) noexcept override {
    if (host_silent) return static_cast<long>(size);  // the host "sends" into the void
    for (std::size_t i = 0; i < size; ++i) {
      std::uint8_t byte = data[i];
      if (!to_board.pass(&byte)) continue;
      if (!(paced_ ? to_board_ring_.push(byte) : board_.send_byte(byte))) return static_cast<long>(i);
    }
    return static_cast<long>(size);
  }

  // Switched by the thread that owns the link, while the world's thread is not running.
  // Back to lock-step, the host's bytes still in the ring go to the board's queue.
  void set_paced(bool paced) noexcept {
    if (!paced) move_to_board();
    paced_ = paced;
  }
  // The world's thread, at each substep: host bytes into the board as its queue takes
  // them; the board's bytes out (dropped past a full ring, as a full UART buffer would).
  void move_to_board() noexcept {
    std::uint8_t byte = 0;
    while (to_board_ring_.peek(&byte) && board_.send_byte(byte)) to_board_ring_.drop_peeked();
  }
  void move_to_host() noexcept {
    std::uint8_t byte = 0;
    while (board_.take_bytes(&byte, 1) == 1) (void)to_host_ring_.push(byte);
  }

  // Garbage straight onto the board's receive line.
  void inject_to_board(const std::uint8_t* data, std::size_t size) noexcept {
    for (std::size_t i = 0; i < size; ++i) board_.send_byte(data[i]);
  }

  WireFaults to_board;
  WireFaults to_host;
  bool host_silent{};

 private:
  SimulatedBoard& board_;
  bool paced_{};
  ByteRing<board_protocol::kQueueBytes> to_board_ring_;
  ByteRing<board_protocol::kQueueBytes> to_host_ring_;
};

}  // namespace hapscene
