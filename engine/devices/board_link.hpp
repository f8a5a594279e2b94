#pragma once
// The host's side of the board protocol (protocol/protocol.h) over a ByteLink:
// handshake, one COMMAND per tick answered by a STATE, sequence-gap and CRC counting,
// round-trip latency, and what to do when the board goes quiet or away.
//
// Every call is non-blocking and allocation-free, so it may run inside the tick. Time is
// passed in (`now_ns`) so a simulated board gives deterministic results.
//
// Faults, and what the link does:
//   corrupt bytes, garbage   the decoder skips them and resyncs (counted)
//   a lost frame             a gap in the board's sequence numbers (counted); the tick
//                            uses the last STATE
//   no valid frame for       "silent": one explicit motor-off COMMAND, then HELLO every
//   silence_timeout_ns       hello_retry_ns until the board answers again
//   read/write error         "vanished": reopen every reopen_retry_ns, then HELLO
//   COMMAND refused as not   the board was reset: HELLO again (its motor stays off until
//   armed                    then); the position is realigned to the nearest sensor
//                            period of the last one
//   no STATE since the       the position is "unmeasured": the loop commands no force
//   (re)connection           until a STATE has arrived
//   no new STATE for         the position is "stale": the loop ramps force out, and in
//   max_position_age_ns      again (soft start) when STATEs come back
//   a STATE out of range or  "implausible" (reading_judge.hpp): rejected (the position
//   farther from the last    stays the last good one), counted and reported, and the loop
//   than the handle can move commands no force until a plausible STATE arrives; judged
//                            so after a reconnection too, once realigned
// Whenever the link comes back, take_restart() tells the loop to ramp force in again.
// Count arithmetic on the board's numbers is done in 64 bits and checked before it
// becomes a 32-bit position.
#include <array>
#include <cmath>
#include <cstdint>

#include "engine/base/latency_histogram.hpp"
#include "engine/devices/byte_link.hpp"
#include "engine/devices/device.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/devices/reading_judge.hpp"
#include "protocol/protocol.h"

namespace hapscene {

struct BoardLinkConfig {
  std::int64_t silence_timeout_ns{50'000'000};
  std::int64_t hello_retry_ns{100'000'000};
  std::int64_t reopen_retry_ns{500'000'000};
  std::int64_t stats_period_ns{250'000'000};  // STATS_REQUEST this often while running
  std::int32_t span_counts{922};              // sensor period, to realign after a reset
  // A position older than this (no new STATE) is stale: force ramps out. Five ticks at
  // 1 kHz: a USB serial adapter delivers STATEs in 1 ms batches, so one or two ticks
  // without one are normal.
  std::int64_t max_position_age_ns{5'000'000};
  // The fastest the handle can move, in counts per second (2 m/s at 13 um per count);
  // a STATE farther from the last one than this allows in the elapsed time plus
  // motion_slack_ns (arrival jitter) is implausible.
  double max_speed_counts_per_s{150'000.0};
  std::int64_t motion_slack_ns{2'000'000};
  // The board's unwrapped count may be at most this many sensor periods from zero (the
  // whole travel of a Hapkit is a few periods), and its raw count at most 1023 (10 bits).
  std::int32_t max_board_periods{64};
};

// The fastest handle motion the link believes, in m/s (see max_speed_counts_per_s).
inline constexpr double kMaxHandleSpeed_m_per_s = 2.0;

// `link` with the sensor period of `profile` (for realigning the position after a reset)
// and the speed bound (kMaxHandleSpeed_m_per_s unless given) in that profile's counts.
inline BoardLinkConfig link_config_for(BoardLinkConfig link, const DeviceProfile& profile,
                                       double max_speed_m_per_s = kMaxHandleSpeed_m_per_s) {
  link.span_counts = profile.sensor.span_counts;
  const double m_per_count = std::abs(compile_kinematics(profile).x_m_per_count);
  if (m_per_count > 0.0 && std::isfinite(m_per_count)) {
    link.max_speed_counts_per_s = max_speed_m_per_s / m_per_count;
  }
  return link;
}


enum class LinkState { handshaking, running, silent, vanished };

enum class LinkEventKind {
  connected,
  silent,
  vanished,
  reopened,
  board_reset,
  refused_version,   // the board answered or refused with another protocol version
  no_position,       // max_position_age_ns after the first COMMAND, still no STATE
  position_stale,    // no new STATE for max_position_age_ns
  implausible_state, // a STATE rejected (out of range, or an impossible jump)
};
inline constexpr std::size_t kLinkEventKinds = 9;

struct LinkEvent {
  std::int64_t t_ns{};
  LinkEventKind kind{};
};

struct LinkCounters {
  std::uint64_t commands_sent{};
  std::uint64_t states_received{};
  std::uint64_t stale_reads{};      // reads with no new STATE since the previous read
  std::uint64_t seq_gaps{};         // board frames missing by sequence number
  std::uint64_t unanswered{};       // COMMANDs whose STATE never came
  std::uint64_t frames_dropped_tx{};  // frames the link would not take whole
  std::uint64_t timeouts_reported{};  // STATEs saying the board's timeout fired
  std::uint64_t duty_limited{};       // STATEs saying the board limited the duty
  std::uint64_t unmeasured_polls{};   // ticks running with no STATE since the connection
  std::uint64_t stale_polls{};        // ticks whose newest STATE was older than the bound
  std::uint64_t implausible_polls{};  // ticks after a rejected STATE (until a good one)
  std::uint64_t implausible_states{}; // STATEs rejected as out of range or impossible jumps
};

// What the board said when the handshake did not complete (for the error message).
struct HandshakeSeen {
  std::uint64_t frames{};             // valid frames of any type
  bool other_version{};               // a HELLO_REPLY with another protocol version
  bool version_known{};               // ... and said which (not just a REFUSED)
  std::uint8_t version{};             // ... that version
  bool refused{};                     // a REFUSED frame
  std::uint8_t refused_type{}, refused_reason{};
  std::uint8_t last_type{};           // type of the last valid frame
  std::uint64_t bad_hello_replies{};  // HELLO_REPLYs of a wrong length
};

class BoardLink {
 public:
  BoardLink(ByteLink& link, const BoardLinkConfig& config);

  // Once per tick: receive(), then count a stale read and act on silence.
  void poll(std::int64_t now_ns) noexcept;
  // Reads and decodes whatever arrived (any number of times per tick); acts on errors.
  void receive(std::int64_t now_ns) noexcept;
  // Sends this tick's command while running (a HELLO, a retry or nothing otherwise).
  void send(const MotorCommand& command, std::int64_t now_ns) noexcept;
  // Asks for the board's statistics now (also sent every stats_period_ns).
  void request_stats() noexcept;

  // The latest position in unwrapped counts, continuous across board resets.
  std::int32_t counts() const noexcept { return counts_; }
  // How far counts() can be trusted, as of the last poll().
  PositionStatus position_status() const noexcept { return position_status_; }
  // What the board sent while handshaking (for a failed handshake's message).
  const HandshakeSeen& handshake_seen() const noexcept { return seen_; }
  LinkState state() const noexcept { return state_; }
  bool identified() const noexcept { return identified_; }
  const hs_hello_reply& identity() const noexcept { return identity_; }
  bool has_stats() const noexcept { return has_stats_; }
  const hs_stats& board_stats() const noexcept { return board_stats_; }
  const hs_decoder& decoder() const noexcept { return decoder_; }
  const LinkCounters& counters() const noexcept { return counters_; }
  const BoardLinkConfig& config() const noexcept { return config_; }
  const LatencyHistogram& round_trip_ns() const noexcept { return round_trip_ns_; }
  // Events in order (at most kMaxEvents kept; later ones only counted).
  static constexpr std::size_t kMaxEvents = 32;
  std::size_t event_count() const noexcept { return event_count_; }
  const LinkEvent& event(std::size_t i) const noexcept { return events_[i]; }
  std::uint64_t events_total() const noexcept { return events_total_; }
  // Events of one kind so far (all of them, kept or only counted).
  std::uint64_t events_of(LinkEventKind kind) const noexcept { return events_by_kind_[static_cast<std::size_t>(kind)]; }

  // True once after the link came back (or first came up): the loop should ramp in.
  bool take_restart() noexcept;
  // True when the link saw a fault the run should fail for (an implausible STATE, or a
  // board that was running and never sent a position).
  bool fault_seen() const noexcept { return counters_.implausible_states > 0 || no_position_seen_; }

 private:
  void on_frame(const hs_frame& frame, std::int64_t now_ns) noexcept;
  void on_state(const hs_frame& frame, std::int64_t now_ns) noexcept;
  bool accept_counts(const hs_state& state, std::int64_t now_ns) noexcept;
  void update_position_status(std::int64_t now_ns) noexcept;
  void start_handshake(LinkState state, std::int64_t now_ns) noexcept;
  void send_frame(std::uint8_t type, const std::uint8_t* payload, std::uint8_t length,
                  std::int64_t now_ns) noexcept;
  void record(LinkEventKind kind, std::int64_t now_ns) noexcept;
  void lost(std::int64_t now_ns) noexcept;

  ByteLink& link_;
  BoardLinkConfig config_;
  hs_decoder decoder_{};
  LinkState state_{LinkState::handshaking};
  std::uint8_t tx_seq_{};
  std::uint8_t rx_seq_expected_{};
  bool rx_seq_known_{};
  std::int64_t last_frame_ns_{};     // last valid frame from the board
  std::int64_t last_hello_ns_{};
  std::int64_t last_reopen_ns_{};
  std::int64_t last_stats_ns_{};
  bool hello_sent_{};
  bool new_state_{};
  bool restart_{};
  bool realign_{};                   // next STATE: keep counts continuous
  bool have_counts_{};
  bool measured_{};                  // a STATE accepted since the last connection
  bool rejected_{};                  // the last STATE was rejected
  bool no_position_seen_{};
  std::int64_t first_command_ns_{-1};  // first COMMAND since the connection (-1: none)
  std::int64_t last_state_ns_{};     // arrival of the last accepted STATE
  PositionStatus position_status_{PositionStatus::unmeasured};
  HandshakeSeen seen_{};
  std::int32_t counts_{};
  std::int32_t offset_counts_{};     // added to the board's unwrapped counts
  bool identified_{};
  hs_hello_reply identity_{};
  bool has_stats_{};
  hs_stats board_stats_{};
  // Send time of each sequence number still waiting for its STATE (-1: none).
  std::array<std::int64_t, 256> sent_ns_{};
  LinkCounters counters_;
  LatencyHistogram round_trip_ns_;
  std::array<LinkEvent, kMaxEvents> events_{};
  std::size_t event_count_{};
  std::uint64_t events_total_{};
  std::array<std::uint64_t, kLinkEventKinds> events_by_kind_{};
};

const char* link_event_name(LinkEventKind kind) noexcept;
const char* link_state_name(LinkState state) noexcept;

// The link's counters as the live view shows them (link_health.hpp).
void fill_link_health(const BoardLink& link, LinkHealth* out) noexcept;

}  // namespace hapscene
