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
    case LinkEventKind::refused_version: return "board refused the protocol version";
  }
  return "?";
}

void BoardLink::record(LinkEventKind kind, std::int64_t now_ns) noexcept {
  ++events_total_;
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

  // Silent: no valid frame for too long. Motor off explicitly, then handshake again.
  if (state_ == LinkState::running && now_ns - last_frame_ns_ > config_.silence_timeout_ns) {
    record(LinkEventKind::silent, now_ns);
    const std::uint8_t off[HS_COMMAND_SIZE] = {0, 0};
    send_frame(HS_TYPE_COMMAND, off, HS_COMMAND_SIZE, now_ns);
    start_handshake(LinkState::silent, now_ns);
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

  switch (frame.type) {
    case HS_TYPE_HELLO_REPLY:
      if (frame.length != HS_HELLO_REPLY_SIZE) return;
      hs_get_hello_reply(frame.payload, &identity_);
      identified_ = true;
      if (identity_.protocol_version != HS_PROTOCOL_VERSION) {
        record(LinkEventKind::refused_version, now_ns);
        return;
      }
      if (state_ != LinkState::running) {
        record(LinkEventKind::connected, now_ns);
        state_ = LinkState::running;
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
      if (frame.payload[1] == HS_REFUSED_NOT_ARMED && state_ == LinkState::running) {
        record(LinkEventKind::board_reset, now_ns);
        start_handshake(LinkState::handshaking, now_ns);
      } else if (frame.payload[1] == HS_REFUSED_VERSION) {
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

  // Position: after a reconnection, shift by whole sensor periods so it stays continuous.
  if (realign_) {
    const double behind = static_cast<double>(counts_) -
                          static_cast<double>(state.unwrapped_counts + offset_counts_);
    offset_counts_ += static_cast<std::int32_t>(std::lround(behind / config_.span_counts)) *
                      config_.span_counts;
    realign_ = false;
  }
  counts_ = state.unwrapped_counts + offset_counts_;
  have_counts_ = true;
  new_state_ = true;
  ++counters_.states_received;
  if (state.status & HS_STATUS_TIMED_OUT) ++counters_.timeouts_reported;
  if (state.status & HS_STATUS_DUTY_LIMITED) ++counters_.duty_limited;
}

}  // namespace hapscene
