#include "engine/devices/serial_hapkit.hpp"

#include <stdexcept>
#include <thread>

#include "engine/base/clock.hpp"
#include "engine/base/format.hpp"
#include "engine/devices/board_report.hpp"

namespace hapscene {

SerialHapkit::SerialHapkit(const DeviceProfile& profile, const SerialConfig& config)
    : port_(config.path, config.baud, "--device serial:" + config.path),
      link_(port_, link_config_for(config.link, profile)),
      start_ns_(monotonic_now_ns()) {
  // The handshake, before the loop starts: HELLO until the board answers.
  const auto deadline_ns =
      start_ns_ + static_cast<std::int64_t>(config.handshake_timeout_s * 1e9);
  while (link_.state() != LinkState::running) {
    const std::int64_t now_ns = monotonic_now_ns();
    if (now_ns > deadline_ns) {
      throw std::runtime_error("--device serial:" + config.path + ": the handshake did not complete within " +
                               printf_string("%g", config.handshake_timeout_s) + " s: " + handshake_failure(link_) +
                               " (is the hapscene firmware flashed, and the baud rate " +
                               std::to_string(config.baud) + "?)");
    }
    link_.send(MotorCommand{}, now_ns);
    link_.poll(now_ns);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

SerialHapkit::~SerialHapkit() {
  if (link_.state() == LinkState::running) link_.send(MotorCommand{}, monotonic_now_ns());
}

std::int32_t SerialHapkit::read() noexcept {
  link_.poll(monotonic_now_ns());
  return link_.counts();
}

void SerialHapkit::write(const MotorCommand& command) noexcept {
  link_.send(command, monotonic_now_ns());
}

std::string SerialHapkit::report() const { return board_report(link_, start_ns_); }

}  // namespace hapscene
