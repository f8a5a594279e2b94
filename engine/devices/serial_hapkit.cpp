#include "engine/devices/serial_hapkit.hpp"

#include "engine/base/clock.hpp"
#include "engine/devices/board_handshake.hpp"
#include "engine/devices/board_report.hpp"

namespace hapscene {

SerialHapkit::SerialHapkit(const DeviceProfile& profile, const SerialConfig& config)
    : port_(config.path, config.baud, "--device serial:" + config.path),
      link_(port_, link_config_for(config.link, profile, config.max_handle_speed_m_per_s)),
      start_ns_(monotonic_now_ns()) {
  // The handshake, before the loop starts: HELLO until the board answers.
  const BoardToOpen board{&link_, "--device serial:" + config.path};
  complete_handshakes(std::span<const BoardToOpen>(&board, 1), config.handshake_timeout_s, config.baud);
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
