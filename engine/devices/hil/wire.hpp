#pragma once
// The serial wire between the host's BoardLink and the simulated board, as a ByteLink,
// with faults a test can inject in either direction: a corrupted byte, dropped bytes,
// injected garbage, or a host that stops sending altogether.
#include <cstdint>

#include "engine/devices/byte_link.hpp"
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
    const std::size_t n = board_.take_bytes(data, capacity);
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
      if (to_board.pass(&byte) && !board_.send_byte(byte)) return static_cast<long>(i);
    }
    return static_cast<long>(size);
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
};

}  // namespace hapscene
