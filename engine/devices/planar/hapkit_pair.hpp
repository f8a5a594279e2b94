#pragma once
// Two Hapkit boards as one 2-DOF device: `--device serial:/dev/ttyACM0,/dev/ttyACM1` for a
// planar profile whose joints are Hapkit-style (an MR sensor or an encoder, a sqrt or
// linear duty drive): the first path is joint 1's board, the second joint 2's, each running
// the hapscene firmware unchanged over its own BoardLink.
//
// Each tick polls both links (non-blocking) and sends both commands; the loop never waits.
// The two links are judged as one device by BoardPair (board_pair.hpp): a stale or lost
// board takes both motors to zero, and both restart together with a soft start.
// The protocol's HELLO_REPLY names the firmware and the MCU type but no per-board identity:
// a profile's board_serials (the boards' USB serial numbers) catch swapped cables; two
// paths naming the same device are refused.
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "engine/devices/board_link.hpp"
#include "engine/devices/planar/board_pair.hpp"
#include "engine/devices/planar/planar_tick.hpp"
#include "engine/devices/serial_port.hpp"

namespace hapscene {

struct HapkitPairConfig {
  std::array<std::string, 2> paths;  // joint 1's board, joint 2's board
  int baud{1000000};
  double handshake_timeout_s{3.0};
  BoardLinkConfig link;              // per link (span and speed bound set per joint)
};

class HapkitPair final : public DeviceOf<2> {
 public:
  // InputError: a profile whose joints are not Hapkit-style, two paths naming one device,
  // a path that cannot be opened; std::runtime_error: a board that does not answer the
  // handshake within the timeout (the message names the joint and the path).
  HapkitPair(const PlanarProfile& profile, const HapkitPairConfig& config);
  // Commands zero force on both motors on the way out.
  ~HapkitPair() override;

  PlanarReading read() noexcept override;
  void write(const PlanarMotorCommand& command) noexcept override;
  bool take_restart() noexcept override { return pair_.take_restart(); }
  PositionStatus position_status() const noexcept override { return pair_.position_status(); }
  bool fault_seen() const noexcept override { return pair_.fault_seen(); }
  std::string report() const override;
  void link_health(DeviceLinkHealth* out) const noexcept override {
    out->links = 2;
    for (std::size_t i = 0; i < 2; ++i) fill_link_health(boards_[i]->link, &out->link[i]);
  }
  std::vector<std::string> link_names() const override { return {paths_[0], paths_[1]}; }

  const BoardLink& link(int joint_index) const noexcept { return boards_[static_cast<std::size_t>(joint_index)]->link; }
  const BoardPair& pair() const noexcept { return pair_; }

 private:
  struct Board {
    Board(const std::string& path, int baud, const std::string& what, const BoardLinkConfig& config)
        : port(path, baud, what), link(port, config) {}
    SerialPort port;
    BoardLink link;
  };

  std::array<std::string, 2> paths_;
  std::array<std::unique_ptr<Board>, 2> boards_;
  BoardPair pair_;
  std::int64_t start_ns_{};
};

// The profile's board_serials against the boards on `paths`: each path's USB serial number
// read from sysfs under `devices_root` ("/"; tests pass a stand-in, as for `hapscene
// devices`). InputError naming the joint and the path when a board is not the one the
// profile names (saying so when the two are swapped, with the order to give), or has no
// serial number to check. Nothing when the profile names none.
void check_board_identities(const PlanarProfile& profile, const std::array<std::string, 2>& paths,
                            const std::string& devices_root);

// The two paths of `serial:A,B` (InputError unless exactly two non-empty paths).
std::array<std::string, 2> parse_board_pair(const std::string& paths_text);

}  // namespace hapscene
