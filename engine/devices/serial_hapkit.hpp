#pragma once
// A real Hapkit on a serial port (`--device serial:/dev/ttyACM0`), running the hapscene
// firmware. Each tick: read what the board sent (non-blocking), hand the loop the latest
// position, send the command. The board unwraps the sensor at 5 kHz, so read()
// gives continuous counts. A silent or vanished board gets zero force and reconnection
// attempts without ever blocking the tick (see BoardLink).
#include <cstdint>
#include <memory>
#include <string>

#include "engine/devices/board_link.hpp"
#include "engine/devices/device.hpp"
#include "engine/devices/profile.hpp"
#include "engine/devices/serial_port.hpp"

namespace hapscene {

struct SerialConfig {
  std::string path;
  int baud{1000000};
  double handshake_timeout_s{3.0};  // an Uno-style board resets when the port opens
  BoardLinkConfig link;
  double max_handle_speed_m_per_s{kMaxHandleSpeed_m_per_s};  // the link's speed bound (see BoardLinkConfig)
};

class SerialHapkit final : public Device {
 public:
  // Opens the port (InputError: bad path or baud) and waits for the handshake outside
  // the loop (std::runtime_error when the board does not answer in time).
  SerialHapkit(const DeviceProfile& profile, const SerialConfig& config);
  // Commands zero force on the way out.
  ~SerialHapkit() override;

  std::int32_t read() noexcept override;
  void write(const MotorCommand& command) noexcept override;
  bool take_restart() noexcept override { return link_.take_restart(); }
  PositionStatus position_status() const noexcept override { return link_.position_status(); }
  bool fault_seen() const noexcept override { return link_.fault_seen(); }
  std::string report() const override;
  void link_health(DeviceLinkHealth* out) const noexcept override {
    out->links = 1;
    fill_link_health(link_, &out->link[0]);
  }
  std::vector<std::string> link_names() const override { return {port_.path()}; }

  const BoardLink& link() const noexcept { return link_; }

 private:
  SerialPort port_;
  BoardLink link_;
  std::int64_t start_ns_{};
};

}  // namespace hapscene
