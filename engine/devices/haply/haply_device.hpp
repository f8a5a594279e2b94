#pragma once
// A Haply 2DIY (or any board running Haply's stock firmware) on a serial port:
// `--device haply:/dev/ttyACM0` with a haply2diy_v1..v3 profile. Opening sends the reset
// and the setup (the arm must be at its reference pose: see the profile's note) and waits
// outside the loop for the first reply. Each tick: poll what the board sent, hand the loop
// the joint angles, send the torques (HaplyLink judges every reply and resynchronises).
// Zero torque goes out when the device closes, and a watchdog process sends it when this
// process dies or stalls (zero_torque_watchdog.hpp).
#include <cstdint>
#include <memory>
#include <string>

#include "engine/devices/haply/haply_link.hpp"
#include "engine/devices/haply/zero_torque_watchdog.hpp"
#include "engine/devices/planar/planar_tick.hpp"
#include "engine/devices/serial_port.hpp"

namespace hapscene {

struct HaplyConfig {
  std::string path;
  std::uint8_t id{kHaplyDefaultId};
  double handshake_timeout_s{3.0};
  HaplyLinkConfig link;
  bool watchdog{true};
  std::int64_t watchdog_stall_ns{100'000'000};
};

class HaplyDevice final : public DeviceOf<2> {
 public:
  // InputError: a bad path, or a profile that is not a Haply-style device;
  // std::runtime_error: the board does not answer within the handshake timeout.
  HaplyDevice(const PlanarProfile& profile, const HaplyConfig& config);
  // Zero torque on the way out (and the watchdog told so).
  ~HaplyDevice() override;

  PlanarReading read() noexcept override;
  void write(const PlanarMotorCommand& command) noexcept override;
  bool take_restart() noexcept override;
  PositionStatus position_status() const noexcept override { return link_.position_status(); }
  bool fault_seen() const noexcept override;
  std::string report() const override;
  void link_health(DeviceLinkHealth* out) const noexcept override;
  std::vector<std::string> link_names() const override { return {port_.path()}; }

  const HaplyLink& link() const noexcept { return link_; }
  pid_t watchdog_pid() const noexcept { return watchdog_ ? watchdog_->pid() : -1; }

 private:
  HaplySetup setup_;  // first: a profile that is not a Haply device is refused before the port opens
  SerialPort port_;
  HaplyLink link_;
  std::unique_ptr<ZeroTorqueWatchdog> watchdog_;
  std::int64_t start_ns_{};
  std::uint64_t handshake_resyncs_{};
  std::uint64_t handshake_implausible_{};
  std::uint64_t watchdog_restarts_{};
};

}  // namespace hapscene
