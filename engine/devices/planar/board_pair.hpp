#pragma once
// Two hapscene-firmware boards judged as one 2-DOF device, one board per joint: shared by
// two real boards on serial ports (`--device serial:A,B`, HapkitPair) and two simulated
// boards in lock-step (`--device hil`, HilPair). The links are owned by the device; the
// pair reads and commands them, and decides for the device as a whole:
//   position_status  the worse of the two joints'; a stale joint beside a fresh one counts
//                    as unmeasured (no force): a pose from one fresh angle and one stale
//                    one is a pose the handle never had
//   write            while that status holds force (unmeasured, implausible), or either
//                    link is not running, both motors get zero, whatever the loop asks
//   take_restart     fires once both links are running again with a fresh position after
//                    either came back or held the force, so the force ramps in (soft
//                    start) on both motors together
//   report           per board, labelled with its joint and name, and the ticks each
//                    board held the device's force
#include <array>
#include <cstdint>
#include <string>

#include "engine/devices/board_link.hpp"
#include "engine/devices/device.hpp"
#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/devices/planar/planar_tick.hpp"

namespace hapscene {

// The fastest a joint turns that the link believes: 40 rad/s (a 5 cm link at 2 m/s).
inline constexpr double kMaxJointSpeed_rad_per_s = 40.0;

// The hapscene firmware drives one Hapkit joint: an MR sensor and a duty drive. InputError,
// starting with `what` (e.g. "--device hil"), for a profile with any other joint.
void require_hapkit_joints(const PlanarProfile& profile, const std::string& what);

// Joint i's link settings: the MR sensor's period (for realigning after a reset) and the
// speed bound in that joint's counts.
BoardLinkConfig joint_link_config(BoardLinkConfig link, const PlanarProfile& profile, std::size_t joint_index);

class BoardPair {
 public:
  BoardPair(BoardLink& joint_1, BoardLink& joint_2) : links_{&joint_1, &joint_2} {}

  // Polls both links (non-blocking) and judges the pair's status.
  PlanarReading read(std::int64_t now_ns) noexcept;
  // Both commands, or zero on both motors (see above).
  void write(const PlanarMotorCommand& command, std::int64_t now_ns) noexcept;
  // Zero force on both motors whose link is running (the device's last word).
  void send_zero(std::int64_t now_ns) noexcept;
  bool take_restart() noexcept;
  PositionStatus position_status() const noexcept { return status_; }
  bool fault_seen() const noexcept { return links_[0]->fault_seen() || links_[1]->fault_seen(); }

  // `names[i]`: joint i's board (its port path, "simulated board 1").
  std::string report(const std::array<std::string, 2>& names, std::int64_t start_ns) const;

  // Ticks the device held force because of each joint's board.
  std::uint64_t held_ticks(int joint_index) const noexcept { return held_ticks_[static_cast<std::size_t>(joint_index)]; }
  // Writes that sent zero to both motors because a board was not running or trusted.
  std::uint64_t zeroed_writes() const noexcept { return zeroed_writes_; }
  std::uint64_t restarts() const noexcept { return restarts_; }

 private:
  bool both_running() const noexcept;
  void update_status() noexcept;

  std::array<BoardLink*, 2> links_;
  PositionStatus status_{PositionStatus::unmeasured};
  bool restart_pending_{};
  bool seen_fresh_{};
  std::array<std::uint64_t, 2> held_ticks_{};
  std::uint64_t zeroed_writes_{};
  std::uint64_t restarts_{};
};

}  // namespace hapscene
