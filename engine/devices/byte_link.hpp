#pragma once
// A byte pipe to a board, never blocking: a serial port (termios) or the simulated
// board's UART. The protocol session (BoardLink) runs on top of it.
#include <cstddef>
#include <cstdint>

namespace hapscene {

class ByteLink {
 public:
  virtual ~ByteLink() = default;
  // Copies up to `capacity` waiting bytes; returns how many (0: none waiting), or -1 when
  // the link is gone (device unplugged, port closed).
  virtual long read_some(std::uint8_t* data, std::size_t capacity) noexcept = 0;
  // Queues up to `size` bytes without waiting; returns how many were taken, or -1 when
  // the link is gone.
  virtual long write_some(const std::uint8_t* data, std::size_t size) noexcept = 0;
  // After -1: tries once to open the link again; true when it is back.
  virtual bool reopen() noexcept { return false; }
};

}  // namespace hapscene
