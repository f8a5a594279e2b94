#include "engine/devices/serial_port.hpp"

#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <pwd.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

struct BaudRate {
  int baud;
  speed_t speed;
};

// The standard rates of Linux termios from 9600 up.
constexpr BaudRate kBaudRates[] = {
    {9600, B9600},       {19200, B19200},     {38400, B38400},     {57600, B57600},
    {115200, B115200},   {230400, B230400},   {460800, B460800},   {500000, B500000},
    {576000, B576000},   {921600, B921600},   {1000000, B1000000}, {1152000, B1152000},
    {1500000, B1500000}, {2000000, B2000000}, {2500000, B2500000}, {3000000, B3000000},
    {3500000, B3500000}, {4000000, B4000000}};

}  // namespace

std::string supported_baud_rates() {
  std::string list;
  for (const BaudRate& rate : kBaudRates) {
    if (!list.empty()) list += ", ";
    list += std::to_string(rate.baud);
  }
  return list;
}

std::string serial_open_failure(const std::string& path, int error) {
  std::string text = std::strerror(error);
  if (error == EACCES || error == EPERM) {
    // The group that owns the port (dialout for USB serial adapters on Debian), and who we are.
    std::string group_name = "dialout";
    struct stat info {};
    if (::stat(path.c_str(), &info) == 0) {
      if (const group* entry = ::getgrgid(info.st_gid); entry != nullptr && entry->gr_name != nullptr) {
        group_name = entry->gr_name;
      }
    }
    std::string user = "$USER";
    if (const passwd* entry = ::getpwuid(::geteuid()); entry != nullptr && entry->pw_name != nullptr) {
      user = entry->pw_name;
    }
    text += " (the port belongs to the group \"" + group_name + "\" and this user is not allowed to use it: run `sudo usermod -aG " +
            group_name + " " + user + "`, then log out and in again so the group takes effect; `groups` lists yours)";
  } else if (error == ENOENT) {
    text += " (no such port: is the board plugged in? `hapscene devices` lists the ports that look like boards)";
  } else if (error == EBUSY) {
    text += " (another program holds the port: close the Arduino serial monitor or stop ModemManager)";
  }
  return text;
}

SerialPort::SerialPort(std::string path, int baud, const std::string& what) : path_(std::move(path)) {
  bool found = false;
  for (const BaudRate& rate : kBaudRates) {
    if (rate.baud == baud) {
      speed_ = rate.speed;
      found = true;
    }
  }
  if (!found) {
    throw InputError("--baud: " + std::to_string(baud) + " is not a rate the serial port offers (" +
                     supported_baud_rates() + ")");
  }
  fd_ = open_configured();
  if (fd_ < 0) throw InputError(what + ": cannot open " + path_ + ": " + serial_open_failure(path_, errno));
}

SerialPort::~SerialPort() { close_port(); }

void SerialPort::close_port() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

// Raw 8N1 at the chosen speed, no flow control, reads that return at once.
int SerialPort::open_configured() noexcept {
  const int fd = ::open(path_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return -1;
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    const int error = errno;
    ::close(fd);
    errno = error;
    return -1;
  }
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS | PARENB);
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  cfsetispeed(&tio, speed_);
  cfsetospeed(&tio, speed_);
  if (tcsetattr(fd, TCSANOW, &tio) != 0) {
    const int error = errno;
    ::close(fd);
    errno = error;
    return -1;
  }
  tcflush(fd, TCIOFLUSH);
  return fd;
}

long SerialPort::read_some(std::uint8_t* data, std::size_t capacity) noexcept {
  if (fd_ < 0) return -1;
  const ssize_t n = ::read(fd_, data, capacity);
  if (n > 0) return n;
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return 0;
  if (n == 0) {
    // With VMIN = VTIME = 0 an empty read returns 0; a hang-up shows in poll().
    pollfd fd{fd_, POLLIN, 0};
    if (::poll(&fd, 1, 0) >= 0 && (fd.revents & (POLLHUP | POLLERR | POLLNVAL)) == 0) return 0;
  }
  // Hung up or an error (EIO, ENXIO): the device went away.
  close_port();
  return -1;
}

long SerialPort::write_some(const std::uint8_t* data, std::size_t size) noexcept {
  if (fd_ < 0) return -1;
  const ssize_t n = ::write(fd_, data, size);
  if (n >= 0) return n;
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return 0;
  close_port();
  return -1;
}

bool SerialPort::reopen() noexcept {
  close_port();
  fd_ = open_configured();
  return fd_ >= 0;
}

}  // namespace hapscene
