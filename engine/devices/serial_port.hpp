#pragma once
// A serial port as a ByteLink: termios raw mode, 8N1, no flow control, non-blocking
// reads and writes (O_NONBLOCK, VMIN = VTIME = 0). A read or write error, or a hang-up
// (the device was unplugged), reports the link gone; reopen() tries the same path again.
#include <string>

#include "engine/devices/byte_link.hpp"

namespace hapscene {

class SerialPort final : public ByteLink {
 public:
  // Throws InputError when the path cannot be opened or configured, or for a baud rate
  // termios does not offer; `what` names the option in messages.
  SerialPort(std::string path, int baud, const std::string& what);
  ~SerialPort() override;
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  long read_some(std::uint8_t* data, std::size_t capacity) noexcept override;
  long write_some(const std::uint8_t* data, std::size_t size) noexcept override;
  bool reopen() noexcept override;

  const std::string& path() const noexcept { return path_; }

 private:
  // Opens and configures; returns the descriptor or -1 with errno set.
  int open_configured() noexcept;
  void close_port() noexcept;

  std::string path_;
  unsigned speed_{};  // termios speed constant
  int fd_{-1};
};

// The baud rates termios offers, for messages ("9600, 19200, ...").
std::string supported_baud_rates();

// Why a port could not be opened, and what to do about it, for `what: cannot open PATH:
// ...`: `error` is the errno of open(). Permission denied names the group that owns the
// port (dialout on Debian) and the command that adds the user to it; a missing port
// points at `hapscene devices`; a busy one names the usual holders.
std::string serial_open_failure(const std::string& path, int error);

}  // namespace hapscene
