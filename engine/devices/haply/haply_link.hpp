#pragma once
// The host's side of the Haply 2DIY stock firmware's protocol (haply_protocol.hpp) over a
// ByteLink: setup, one torque frame per tick answered by one reply, and what to do when
// the bytes stop making sense. The protocol has no framing and no checksum, so the link
// judges each reply by what it can check:
//   a reply whose first byte is not the device id     "wrong id"     resync
//   an angle that is not a finite number              "corrupt"      resync
//   an angle more than a turn from the joint's board  "jump"         resync
//     offset, or farther from the last one than the
//     arm can turn in the time between them
//   a reply begun but not completed in short_reply_ns "short reply"  resync
//   no reply at all for silence_ns                    "silence"      resync (again every
//                                                                    silence_ns until one comes)
//   more than 64 replies' worth of unread bytes       "overflow"     resync
//   a read or write error (unplugged)                 "vanished"     reopen every
//                                                                    reopen_retry_ns, then resync
// A resync: a zero-torque frame, a reset, the setup again, a quiet time in which every
// byte that arrives is dropped (replies to frames sent before), then zero-torque requests
// one at a time until two replies in a row come back exactly (nine bytes and no more, the
// id); anything else runs the setup again (counted as a setup retry). The setup presets the
// board's encoders to their offsets, so each of those replies is judged as above against
// the one before it, the first against the offsets at the time the setup went out: a
// board that answers the setup with absurd angles (3e17 deg, NaN, a jump) is set up again,
// never trusted. Every reply rejected so (in any state) is counted as implausible, with
// the first's time and kind, and reported (reading_judge.hpp makes the judgement).
// Since the setup presets the encoders wherever the arm is, after a resync
// the link carries an angle correction per joint that makes the first angles continue
// the last trusted ones (the arm moves little in the few ms a resync takes); every resync
// is counted by its reason and reported.
// Between a fault and the first good reply after its resync the position is "unmeasured"
// (no force) and every frame sent is a zero torque; take_restart() then asks the loop to
// ramp force in again. A position older than max_angle_age_ns is "stale" (force ramps out).
// Every call is non-blocking and allocation-free; time is passed in (deterministic tests).
#include <array>
#include <cstdint>
#include <string>

#include "engine/base/axes.hpp"
#include "engine/devices/byte_link.hpp"
#include "engine/devices/device.hpp"
#include "engine/devices/haply/haply_protocol.hpp"
#include "engine/devices/reading_judge.hpp"

namespace hapscene {

inline constexpr std::size_t kHaplyRxReplies = 64;  // replies the link can hold unread

struct HaplyLinkConfig {
  std::int64_t max_angle_age_ns{5'000'000};    // older: stale (force ramps out)
  std::int64_t short_reply_ns{5'000'000};      // a partial reply not completed in this: short
  std::int64_t silence_ns{50'000'000};         // no reply at all for this long: silence
  std::int64_t resync_quiet_ns{5'000'000};     // after reset and setup, bytes are dropped for this long
  std::int64_t reopen_retry_ns{500'000'000};
  // The fastest a joint turns, in rad/s (a pantograph's proximal link flicked by hand turns
  // well under 30 rad/s), and the arrival jitter allowed on top of the time between replies.
  double max_joint_speed_rad_per_s{60.0};
  std::int64_t motion_slack_ns{3'000'000};
  // A joint reads within this of its board offset (the board counts from the offset at
  // the setup, and no joint of a pantograph turns a whole turn).
  double max_turn_from_offset_deg{360.0};
};

enum class HaplyResyncReason : std::uint8_t { wrong_id, corrupt, jump, short_reply, silence, overflow, vanished };
inline constexpr int kHaplyResyncReasons = 7;
const char* haply_resync_reason_name(HaplyResyncReason reason) noexcept;

enum class HaplyLinkState : std::uint8_t { configuring, running, vanished };

struct HaplyLinkCounters {
  std::uint64_t frames_sent{};
  std::uint64_t frames_dropped{};     // found the send queue full: not sent at all
  std::uint64_t partial_writes{};     // writes the port took only in part (the rest queued)
  std::uint64_t replies{};            // whole replies accepted
  std::uint64_t bytes_dropped{};      // dropped while resynchronising or after a fault
  std::uint64_t resyncs{};
  std::array<std::uint64_t, kHaplyResyncReasons> by_reason{};
  std::uint64_t unmeasured_polls{};   // ticks with no position (configuring, vanished)
  std::uint64_t stale_polls{};        // ticks whose newest reply was older than the bound
  std::uint64_t setup_retries{};      // setups run again because their replies did not come back exactly
  std::uint64_t implausible{};        // replies whose angles judge_reading() rejected
  std::int64_t first_implausible_ns{-1};
  ReadingFault first_implausible_fault{};
  std::int64_t first_resync_ns{-1};   // when the first resync began (-1: none)
  HaplyResyncReason first_reason{};
};

class HaplyLink {
 public:
  // Sends the reset and setup at once (the arm must be at its reference pose).
  HaplyLink(ByteLink& link, const HaplySetup& setup, const HaplyLinkConfig& config, std::int64_t now_ns) noexcept;

  // Once per tick before the loop uses angles(): reads and judges what arrived.
  void poll(std::int64_t now_ns) noexcept;
  // Once per tick: this tick's torques per joint (N m; zero while not running).
  void send(const Vec2& joint_torque_N_m, std::int64_t now_ns) noexcept;
  // A zero-torque frame now, whatever the state (the end of a run).
  void send_zero() noexcept;
  // Outside the loop (the end of a run): waits up to `attempts` ms for the port to take
  // every queued byte; true when it did.
  bool drain_tx(int attempts) noexcept;

  Vec2 angles_deg() const noexcept { return angles_deg_; }   // with the correction
  PositionStatus position_status() const noexcept { return status_; }
  HaplyLinkState state() const noexcept { return state_; }
  bool take_restart() noexcept {
    const bool restart = restart_pending_;
    restart_pending_ = false;
    return restart;
  }
  bool ever_running() const noexcept { return ever_running_; }
  const HaplyLinkCounters& counters() const noexcept { return counters_; }
  Vec2 correction_deg() const noexcept { return correction_deg_; }

  // Summary lines (outside the loop); `start_ns` is when the run began.
  std::string report(std::int64_t start_ns) const;

 private:
  void begin_resync(HaplyResyncReason reason, std::int64_t now_ns) noexcept;
  void restart_setup(std::int64_t now_ns) noexcept;
  void send_request(std::int64_t now_ns) noexcept;
  ReadingFault judge(const Vec2& board_deg, std::int64_t now_ns) const noexcept;
  void count_implausible(ReadingFault fault, std::int64_t now_ns) noexcept;
  void send_frame(const HaplyFrame& frame) noexcept;
  bool flush_tx() noexcept;  // true when nothing is left queued
  void accept(const Vec2& board_deg, std::int64_t now_ns) noexcept;

  ByteLink& link_;
  HaplySetup setup_;
  HaplyLinkConfig config_;
  HaplyLinkState state_{HaplyLinkState::configuring};
  PositionStatus status_{PositionStatus::unmeasured};
  HaplyLinkCounters counters_;

  // Room for a burst of replies (a board or a USB adapter that delivers several at once):
  // all are judged and the newest is used; more than this unread is an overflow.
  std::array<std::uint8_t, kHaplyRxReplies * kHaplyReplyBytes> rx_{};
  std::array<std::uint8_t, 16 * kHaplyMaxSetupBytes> tx_{};  // bytes queued for the port
  std::size_t tx_size_{};
  std::size_t rx_size_{};
  std::int64_t rx_partial_since_ns_{-1};   // when the pending partial reply began

  std::int64_t configured_ns_{};           // when the last reset and setup went out
  bool request_sent_{};                    // configuring: a zero-torque request is out
  bool have_candidate_{};                  // configuring: the first of two replies came
  // The board's angles the next reply is judged against, and when they held: the offsets
  // when the setup went out, then each reply accepted (board terms, no correction).
  Vec2 reference_deg_{};
  std::int64_t reference_ns_{};
  std::int64_t last_reply_ns_{-1};
  int outstanding_{};                      // frames sent and not yet answered
  std::int64_t waiting_since_ns_{-1};      // since when a frame has waited for its reply (-1: none)
  std::int64_t last_reopen_ns_{};
  Vec2 angles_deg_{};                      // corrected, the last trusted
  Vec2 correction_deg_{};
  bool have_trusted_{};                    // angles_deg_ holds a trusted pose
  bool realign_{};                         // the next accepted reply sets the correction
  bool restart_pending_{};
  bool ever_running_{};
};

}  // namespace hapscene
