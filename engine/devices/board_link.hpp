#pragma once
// The host's side of the board protocol (engine/firmware/protocol.h) over a ByteLink:
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
// Whenever the link comes back, take_restart() tells the loop to ramp force in again.
#include <array>
#include <cstdint>

#include "engine/devices/byte_link.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/firmware/protocol.h"
#include "engine/run/latency_histogram.hpp"

namespace hapscene {

struct BoardLinkConfig {
  std::int64_t silence_timeout_ns{50'000'000};
  std::int64_t hello_retry_ns{100'000'000};
  std::int64_t reopen_retry_ns{500'000'000};
  std::int64_t stats_period_ns{250'000'000};  // STATS_REQUEST this often while running
  std::int32_t span_counts{922};              // sensor period, to realign after a reset
};

// `link` with the sensor period of `profile` (for realigning the position after a reset).
inline BoardLinkConfig link_config_for(BoardLinkConfig link, const DeviceProfile& profile) {
  link.span_counts = profile.sensor.span_counts;
  return link;
}

enum class LinkState { handshaking, running, silent, vanished };

enum class LinkEventKind { connected, silent, vanished, reopened, board_reset, refused_version };

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
  LinkState state() const noexcept { return state_; }
  bool identified() const noexcept { return identified_; }
  const hs_hello_reply& identity() const noexcept { return identity_; }
  bool has_stats() const noexcept { return has_stats_; }
  const hs_stats& board_stats() const noexcept { return board_stats_; }
  const hs_decoder& decoder() const noexcept { return decoder_; }
  const LinkCounters& counters() const noexcept { return counters_; }
  const LatencyHistogram& round_trip_ns() const noexcept { return round_trip_ns_; }
  // Events in order (at most kMaxEvents kept; later ones only counted).
  static constexpr std::size_t kMaxEvents = 32;
  std::size_t event_count() const noexcept { return event_count_; }
  const LinkEvent& event(std::size_t i) const noexcept { return events_[i]; }
  std::uint64_t events_total() const noexcept { return events_total_; }

  // True once after the link came back (or first came up): the loop should ramp in.
  bool take_restart() noexcept;

 private:
  void on_frame(const hs_frame& frame, std::int64_t now_ns) noexcept;
  void on_state(const hs_frame& frame, std::int64_t now_ns) noexcept;
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
};

const char* link_event_name(LinkEventKind kind) noexcept;

}  // namespace hapscene
