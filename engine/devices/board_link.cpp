#include "engine/devices/board_link.hpp"

#include <algorithm>
#include <cmath>

namespace hapscene {

BoardLink::BoardLink(ByteLink& link, const BoardLinkConfig& config) : link_(link), config_(config) {
  hs_decoder_init(&decoder_);
  sent_ns_.fill(-1);
}

const char* link_event_name(LinkEventKind kind) noexcept {
  switch (kind) {
    case LinkEventKind::connected: return "connected";
    case LinkEventKind::silent: return "silent (no reply): motor off, handshaking again";
    case LinkEventKind::vanished: return "vanished (port error): motor off, reopening";
    case LinkEventKind::reopened: return "port reopened";
    case LinkEventKind::board_reset: return "board was reset: handshaking again";
    case LinkEventKind::refused_version: return "board speaks another protocol version";
    case LinkEventKind::no_position: return "no position from the board since the connection: no force";
    case LinkEventKind::position_stale: return "position stale (no new STATE): force ramped out";
    case LinkEventKind::implausible_state: return "implausible position from the board (rejected): no force";
  }
  return "?";
}

const char* link_state_name(LinkState state) noexcept {
  switch (state) {
    case LinkState::handshaking: return "handshaking";
    case LinkState::running: return "running";
    case LinkState::silent: return "silent";
    case LinkState::vanished: return "vanished";
  }
  return "?";
}

void fill_link_health(const BoardLink& link, LinkHealth* out) noexcept {
  const LinkCounters& c = link.counters();
  const hs_decoder& d = link.decoder();
  LinkHealth h;
  h.protocol = "hapscene";
  h.state = link_state_name(link.state());
  h.commands = c.commands_sent;
  h.replies = c.states_received;
  h.crc_errors = d.crc_errors;
  h.length_errors = d.length_errors;
  h.bytes_skipped = d.bytes_skipped;
  h.lost_frames = c.seq_gaps;
  h.unanswered = c.unanswered;
  h.frames_not_sent = c.frames_dropped_tx;
  h.stale_reads = c.stale_reads;
  h.board_timeouts = c.timeouts_reported;
  h.implausible = c.implausible_states;
  h.connects = link.events_of(LinkEventKind::connected);
  h.board_resets = link.events_of(LinkEventKind::board_reset);
  h.silences = link.events_of(LinkEventKind::silent);
  h.vanished = link.events_of(LinkEventKind::vanished);
  const LatencyHistogram& rtt = link.round_trip_ns();
  h.round_trip_count = rtt.count();
  h.round_trip_sum_ns = rtt.sum_ns();
  h.round_trip_max_ns = rtt.max_ns();
  h.board_stats = link.has_stats();
  if (h.board_stats) {
    const hs_stats& s = link.board_stats();
    h.board_frames = s.frames_ok;
    h.board_crc_errors = s.crc_errors;
    h.board_length_errors = s.length_errors;
    h.board_bytes_skipped = s.bytes_skipped;
    h.board_lost_frames = s.seq_gaps;
    h.board_command_timeouts = s.timeouts;
  }
  *out = h;
}

void BoardLink::record(LinkEventKind kind, std::int64_t now_ns) noexcept {
  ++events_total_;
  ++events_by_kind_[static_cast<std::size_t>(kind)];
  if (event_count_ < kMaxEvents) events_[event_count_++] = LinkEvent{now_ns, kind};
}

bool BoardLink::take_restart() noexcept {
  const bool restart = restart_;
  restart_ = false;
  return restart;
}

// Back to the handshake: the board's sequence numbers may restart, and answers to old
// commands no longer count.
void BoardLink::start_handshake(LinkState state, std::int64_t now_ns) noexcept {
  state_ = state;
  hello_sent_ = false;
  rx_seq_known_ = false;
  last_frame_ns_ = now_ns;
  measured_ = false;
  rejected_ = false;
  sent_ns_.fill(-1);
}

void BoardLink::lost(std::int64_t now_ns) noexcept {
  if (state_ == LinkState::vanished) return;
  record(LinkEventKind::vanished, now_ns);
  state_ = LinkState::vanished;
  last_reopen_ns_ = now_ns;
}

void BoardLink::receive(std::int64_t now_ns) noexcept {
  // Vanished: try to reopen now and then; nothing to read until then.
  if (state_ == LinkState::vanished) {
    if (now_ns - last_reopen_ns_ < config_.reopen_retry_ns) return;
    last_reopen_ns_ = now_ns;
    if (!link_.reopen()) return;
    record(LinkEventKind::reopened, now_ns);
    hs_decoder_init(&decoder_);
    start_handshake(LinkState::handshaking, now_ns);
  }

  // Read what is waiting (a bounded number of reads) and decode it.
  std::uint8_t buffer[256];
  for (int reads = 0; reads < 16; ++reads) {
    const long n = link_.read_some(buffer, sizeof buffer);
    if (n < 0) {
      lost(now_ns);
      return;
    }
    for (long i = 0; i < n; ++i) {
      hs_decoder_push(&decoder_, buffer[i]);
      hs_frame frame;
      while (hs_decoder_poll(&decoder_, &frame)) on_frame(frame, now_ns);
    }
    if (n < static_cast<long>(sizeof buffer)) break;
  }
}

void BoardLink::poll(std::int64_t now_ns) noexcept {
  receive(now_ns);
  if (state_ == LinkState::running && !new_state_) ++counters_.stale_reads;
  new_state_ = false;
  update_position_status(now_ns);

  // Silent: no valid frame for too long. Motor off explicitly, then handshake again.
  if (state_ == LinkState::running && now_ns - last_frame_ns_ > config_.silence_timeout_ns) {
    record(LinkEventKind::silent, now_ns);
    const std::uint8_t off[HS_COMMAND_SIZE] = {0, 0};
    send_frame(HS_TYPE_COMMAND, off, HS_COMMAND_SIZE, now_ns);
    start_handshake(LinkState::silent, now_ns);
  }
}

// Whether this tick may use counts(): counted per tick, with an event when a position
// goes missing or stale (once per episode).
void BoardLink::update_position_status(std::int64_t now_ns) noexcept {
  const PositionStatus before = position_status_;
  if (state_ == LinkState::running && rejected_) {
    position_status_ = PositionStatus::implausible;
  } else if (state_ != LinkState::running || !measured_) {
    position_status_ = PositionStatus::unmeasured;
  } else if (now_ns - last_state_ns_ > config_.max_position_age_ns) {
    position_status_ = PositionStatus::stale;
  } else {
    position_status_ = PositionStatus::fresh;
  }
  switch (position_status_) {
    case PositionStatus::fresh: break;
    case PositionStatus::unmeasured:
      if (state_ != LinkState::running) break;  // reconnecting: its own events say so
      ++counters_.unmeasured_polls;
      // Timed from the first COMMAND: the loop may start well after the handshake.
      if (first_command_ns_ >= 0 && now_ns - first_command_ns_ > config_.max_position_age_ns &&
          !no_position_seen_) {
        no_position_seen_ = true;
        record(LinkEventKind::no_position, now_ns);
      }
      break;
    case PositionStatus::stale:
      ++counters_.stale_polls;
      if (before != PositionStatus::stale) record(LinkEventKind::position_stale, now_ns);
      break;
    case PositionStatus::implausible: ++counters_.implausible_polls; break;
  }
}

void BoardLink::send(const MotorCommand& command, std::int64_t now_ns) noexcept {
  switch (state_) {
    case LinkState::vanished:
      return;
    case LinkState::handshaking:
    case LinkState::silent:
      // HELLO, repeated until the board answers.
      if (!hello_sent_ || now_ns - last_hello_ns_ >= config_.hello_retry_ns) {
        const std::uint8_t version = HS_PROTOCOL_VERSION;
        send_frame(HS_TYPE_HELLO, &version, 1, now_ns);
        hello_sent_ = true;
        last_hello_ns_ = now_ns;
      }
      return;
    case LinkState::running:
      break;
  }

  // The command: duty in 1/255 steps, the enable flag only when there is a duty.
  const auto duty =
      static_cast<std::uint8_t>(std::lround(std::clamp(command.duty, 0.0, 1.0) * 255.0));
  hs_command wire{duty, 0};
  if (duty > 0) wire.flags |= HS_COMMAND_ENABLE;
  if (command.direction_high) wire.flags |= HS_COMMAND_DIRECTION_HIGH;
  std::uint8_t payload[HS_COMMAND_SIZE];
  hs_put_command(&wire, payload);
  if (first_command_ns_ < 0) first_command_ns_ = now_ns;
  if (sent_ns_[tx_seq_] >= 0) ++counters_.unanswered;
  sent_ns_[tx_seq_] = now_ns;
  send_frame(HS_TYPE_COMMAND, payload, HS_COMMAND_SIZE, now_ns);
  ++counters_.commands_sent;

  // The board's statistics, now and then.
  if (now_ns - last_stats_ns_ >= config_.stats_period_ns) {
    last_stats_ns_ = now_ns;
    request_stats();
  }
}

void BoardLink::request_stats() noexcept {
  if (state_ != LinkState::running) return;
  send_frame(HS_TYPE_STATS_REQUEST, nullptr, 0, 0);
}

void BoardLink::send_frame(std::uint8_t type, const std::uint8_t* payload, std::uint8_t length,
                           std::int64_t now_ns) noexcept {
  std::uint8_t frame[HS_MAX_FRAME]{};
  const std::uint8_t size = hs_encode_frame(type, tx_seq_, payload, length, frame);
  tx_seq_ = static_cast<std::uint8_t>(tx_seq_ + 1);
  const long written = link_.write_some(frame, size);
  if (written < 0) {
    lost(now_ns);
  } else if (written < size) {
    ++counters_.frames_dropped_tx;  // a partial frame: the board's decoder skips it
  }
}

void BoardLink::on_frame(const hs_frame& frame, std::int64_t now_ns) noexcept {
  // Any valid frame shows the board is alive; gaps in its numbering are lost frames.
  last_frame_ns_ = now_ns;
  if (rx_seq_known_ && frame.seq != rx_seq_expected_) {
    counters_.seq_gaps += static_cast<std::uint8_t>(frame.seq - rx_seq_expected_);
  }
  rx_seq_known_ = true;
  rx_seq_expected_ = static_cast<std::uint8_t>(frame.seq + 1);
  ++seen_.frames;
  seen_.last_type = frame.type;

  switch (frame.type) {
    case HS_TYPE_HELLO_REPLY:
      // The first byte is the protocol version in every version; the rest is ours only
      // when the version is.
      if (frame.length >= 1 && frame.payload[0] != HS_PROTOCOL_VERSION) {
        if (!seen_.other_version) record(LinkEventKind::refused_version, now_ns);
        seen_.other_version = true;
        seen_.version_known = true;
        seen_.version = frame.payload[0];
        if (frame.length == HS_HELLO_REPLY_SIZE) {
          hs_get_hello_reply(frame.payload, &identity_);
          identified_ = true;
        }
        return;
      }
      if (frame.length != HS_HELLO_REPLY_SIZE) {
        ++seen_.bad_hello_replies;
        return;
      }
      hs_get_hello_reply(frame.payload, &identity_);
      identified_ = true;
      if (state_ != LinkState::running) {
        record(LinkEventKind::connected, now_ns);
        state_ = LinkState::running;
        first_command_ns_ = -1;
        measured_ = false;
        rejected_ = false;
        restart_ = true;
        realign_ = have_counts_;
        sent_ns_.fill(-1);
        last_stats_ns_ = now_ns;
        request_stats();
      }
      return;
    case HS_TYPE_STATE:
      on_state(frame, now_ns);
      return;
    case HS_TYPE_STATS:
      if (frame.length != HS_STATS_SIZE) return;
      hs_get_stats(frame.payload, &board_stats_);
      has_stats_ = true;
      return;
    case HS_TYPE_REFUSED:
      if (frame.length != 2) return;
      seen_.refused = true;
      seen_.refused_type = frame.payload[0];
      seen_.refused_reason = frame.payload[1];
      if (frame.payload[1] == HS_REFUSED_NOT_ARMED && state_ == LinkState::running) {
        record(LinkEventKind::board_reset, now_ns);
        start_handshake(LinkState::handshaking, now_ns);
      } else if (frame.payload[1] == HS_REFUSED_VERSION && !seen_.other_version) {
        seen_.other_version = true;  // its version is unknown: it did not say
        record(LinkEventKind::refused_version, now_ns);
      }
      return;
    default:
      return;
  }
}

void BoardLink::on_state(const hs_frame& frame, std::int64_t now_ns) noexcept {
  if (frame.length != HS_STATE_SIZE) return;
  hs_state state;
  hs_get_state(frame.payload, &state);

  // Round trip: from sending the COMMAND to its STATE arriving.
  std::int64_t& sent_ns = sent_ns_[state.echo_seq];
  if (sent_ns >= 0) {
    round_trip_ns_.record(static_cast<std::uint64_t>(std::max<std::int64_t>(0, now_ns - sent_ns)));
    sent_ns = -1;
  }

  // Position: checked before it is used (a rejected STATE leaves the last position).
  if (!accept_counts(state, now_ns)) {
    ++counters_.implausible_states;
    if (!rejected_) record(LinkEventKind::implausible_state, now_ns);
    rejected_ = true;
  } else {
    rejected_ = false;
    measured_ = true;
    last_state_ns_ = now_ns;
  }
  new_state_ = true;
  ++counters_.states_received;
  if (state.status & HS_STATUS_TIMED_OUT) ++counters_.timeouts_reported;
  if (state.status & HS_STATUS_DUTY_LIMITED) ++counters_.duty_limited;
}


// The board's reading becomes counts_ only when judge_reading() finds it plausible: its
// unwrapped count within max_board_periods of zero, and its step from the last accepted
// position (after a reconnection too, once realigned) within the speed bound. Every sum is
// formed in 64 bits from 32-bit inputs (so it cannot overflow) and must fit 32 bits.
bool BoardLink::accept_counts(const hs_state& state, std::int64_t now_ns) noexcept {
  constexpr std::uint16_t kMaxRawCounts = 1023;  // 10-bit ADC
  if (state.raw_counts > kMaxRawCounts) return false;
  const std::int64_t span = config_.span_counts;
  const std::int64_t board = state.unwrapped_counts;

  std::int64_t offset = offset_counts_;
  if (realign_) {
    // After a reconnection: shift by whole sensor periods so the position stays
    // continuous with the last one.
    const std::int64_t behind = static_cast<std::int64_t>(counts_) - (board + offset);
    const std::int64_t periods = span > 0 ? std::llround(static_cast<double>(behind) / static_cast<double>(span)) : 0;
    offset += periods * span;
  }
  // The last accepted position in this reading's terms (board counts with this offset).
  const double board_limit = static_cast<double>(config_.max_board_periods) * static_cast<double>(span);
  const ReadingBounds bounds{-board_limit, board_limit, config_.max_speed_counts_per_s, config_.motion_slack_ns};
  const TrustedReading last{static_cast<double>(static_cast<std::int64_t>(counts_) - offset), last_state_ns_};
  if (judge_reading(bounds, static_cast<double>(board), have_counts_ ? &last : nullptr, now_ns) != ReadingFault::none) {
    return false;
  }
  const std::int64_t counts = board + offset;
  constexpr std::int64_t kMin = INT32_MIN, kMax = INT32_MAX;
  if (counts < kMin || counts > kMax || offset < kMin || offset > kMax) return false;
  offset_counts_ = static_cast<std::int32_t>(offset);
  counts_ = static_cast<std::int32_t>(counts);
  realign_ = false;
  have_counts_ = true;
  return true;
}

}  // namespace hapscene
