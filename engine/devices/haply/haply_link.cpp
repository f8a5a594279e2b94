#include "engine/devices/haply/haply_link.hpp"

#include <cmath>
#include <cstring>
#include <ctime>
#include <numbers>

#include "engine/base/format.hpp"

namespace hapscene {

const char* haply_resync_reason_name(HaplyResyncReason reason) noexcept {
  switch (reason) {
    case HaplyResyncReason::wrong_id: return "wrong id";
    case HaplyResyncReason::corrupt: return "corrupt";
    case HaplyResyncReason::jump: return "jump";
    case HaplyResyncReason::short_reply: return "short reply";
    case HaplyResyncReason::silence: return "silence";
    case HaplyResyncReason::overflow: return "overflow";
    case HaplyResyncReason::vanished: return "vanished";
  }
  return "?";
}

HaplyLink::HaplyLink(ByteLink& link, const HaplySetup& setup, const HaplyLinkConfig& config,
                     std::int64_t now_ns) noexcept
    : link_(link), setup_(setup), config_(config) {
  restart_setup(now_ns);
}

// Frames go out whole or not at all: a port that takes part of one keeps the rest queued
// and sent before anything else, because the board, which has no framing, would read the
// next frame's bytes as the rest of this one (torques made of the wrong bytes). A frame
// that finds the queue full is dropped whole and counted.
void HaplyLink::send_frame(const HaplyFrame& frame) noexcept {
  if (state_ == HaplyLinkState::vanished) return;
  flush_tx();
  if (tx_size_ + frame.size > tx_.size()) {
    ++counters_.frames_dropped;
    return;
  }
  std::memcpy(tx_.data() + tx_size_, frame.bytes.data(), frame.size);
  tx_size_ += frame.size;
  ++counters_.frames_sent;
  flush_tx();
}

bool HaplyLink::flush_tx() noexcept {
  while (tx_size_ > 0) {
    const long n = link_.write_some(tx_.data(), tx_size_);
    if (n <= 0) return false;  // would block (or gone: the next poll sees it)
    const auto written = static_cast<std::size_t>(n);
    std::memmove(tx_.data(), tx_.data() + written, tx_size_ - written);
    tx_size_ -= written;
    if (tx_size_ > 0) ++counters_.partial_writes;
  }
  return true;
}

bool HaplyLink::drain_tx(int attempts) noexcept {
  for (int i = 0; i < attempts; ++i) {
    if (flush_tx()) return true;
    timespec pause{0, 1'000'000};
    nanosleep(&pause, nullptr);
  }
  return tx_size_ == 0;
}

// One zero-torque frame whose reply the setup waits for.
void HaplyLink::send_request(std::int64_t now_ns) noexcept {
  send_frame(encode_torques(setup_, Vec2{}));
  request_sent_ = true;
  outstanding_ = 1;
  waiting_since_ns_ = now_ns;
}

// A reply's angles (board terms) against each joint's range around its board offset and
// against the reference at the joints' top speed; the first fault found (a non-finite
// angle on either joint first: the other's step says nothing about it).
ReadingFault HaplyLink::judge(const Vec2& board_deg, std::int64_t now_ns) const noexcept {
  if (!std::isfinite(board_deg[0]) || !std::isfinite(board_deg[1])) return ReadingFault::not_finite;
  const double speed_deg_per_s = config_.max_joint_speed_rad_per_s * (180.0 / std::numbers::pi);
  for (std::size_t i = 0; i < 2; ++i) {
    const double offset_deg = setup_.encoder_offset_deg[i];
    const ReadingBounds bounds{offset_deg - config_.max_turn_from_offset_deg,
                               offset_deg + config_.max_turn_from_offset_deg, speed_deg_per_s,
                               config_.motion_slack_ns};
    const TrustedReading last{reference_deg_[static_cast<int>(i)], reference_ns_};
    const ReadingFault fault = judge_reading(bounds, board_deg[static_cast<int>(i)], &last, now_ns);
    if (fault != ReadingFault::none) return fault;
  }
  return ReadingFault::none;
}

void HaplyLink::count_implausible(ReadingFault fault, std::int64_t now_ns) noexcept {
  if (counters_.implausible++ == 0) {
    counters_.first_implausible_ns = now_ns;
    counters_.first_implausible_fault = fault;
  }
}

void HaplyLink::send_zero() noexcept { send_frame(encode_torques(setup_, Vec2{})); }

// Zero torque, reset, setup; then a quiet time before the first request.
void HaplyLink::restart_setup(std::int64_t now_ns) noexcept {
  state_ = HaplyLinkState::configuring;
  status_ = PositionStatus::unmeasured;
  send_frame(encode_torques(setup_, Vec2{}));
  send_frame(encode_reset());
  send_frame(encode_setup(setup_));
  counters_.bytes_dropped += rx_size_;
  rx_size_ = 0;
  rx_partial_since_ns_ = -1;
  configured_ns_ = now_ns;
  request_sent_ = false;
  have_candidate_ = false;
  // The board reads its offsets from now on, wherever the arm is.
  reference_deg_ = Vec2{{setup_.encoder_offset_deg[0], setup_.encoder_offset_deg[1]}};
  reference_ns_ = now_ns;
  outstanding_ = 0;
  waiting_since_ns_ = -1;
}

void HaplyLink::begin_resync(HaplyResyncReason reason, std::int64_t now_ns) noexcept {
  ++counters_.resyncs;
  ++counters_.by_reason[static_cast<std::size_t>(reason)];
  if (counters_.first_resync_ns < 0) {
    counters_.first_resync_ns = now_ns;
    counters_.first_reason = reason;
  }
  if (have_trusted_) realign_ = true;
  if (reason == HaplyResyncReason::vanished) {
    state_ = HaplyLinkState::vanished;
    status_ = PositionStatus::unmeasured;
    counters_.bytes_dropped += rx_size_;
    rx_size_ = 0;
    last_reopen_ns_ = now_ns;
    return;
  }
  restart_setup(now_ns);
}

void HaplyLink::accept(const Vec2& board_deg, std::int64_t now_ns) noexcept {
  if (realign_) {
    correction_deg_ = angles_deg_ - board_deg;
    realign_ = false;
  }
  angles_deg_ = board_deg + correction_deg_;
  reference_deg_ = board_deg;
  reference_ns_ = now_ns;
  have_trusted_ = true;
  last_reply_ns_ = now_ns;
  ++counters_.replies;
  if (outstanding_ > 0) --outstanding_;
  waiting_since_ns_ = outstanding_ > 0 ? now_ns : -1;
}

void HaplyLink::poll(std::int64_t now_ns) noexcept {
  // Unplugged: try to open the port again now and then, and set the board up anew.
  if (state_ == HaplyLinkState::vanished) {
    ++counters_.unmeasured_polls;
    if (now_ns - last_reopen_ns_ >= config_.reopen_retry_ns) {
      last_reopen_ns_ = now_ns;
      if (link_.reopen()) {
        state_ = HaplyLinkState::configuring;
        restart_setup(now_ns);
      }
    }
    return;
  }

  // Everything that arrived; more than the buffer holds means the stream makes no sense.
  for (;;) {
    std::uint8_t chunk[64];
    const long n = link_.read_some(chunk, sizeof chunk);
    if (n < 0) {
      begin_resync(HaplyResyncReason::vanished, now_ns);
      ++counters_.unmeasured_polls;
      return;
    }
    if (n == 0) break;
    const auto count = static_cast<std::size_t>(n);
    if (rx_size_ + count > rx_.size()) {
      counters_.bytes_dropped += count;
      begin_resync(HaplyResyncReason::overflow, now_ns);
      ++counters_.unmeasured_polls;
      return;
    }
    std::memcpy(rx_.data() + rx_size_, chunk, count);
    rx_size_ += count;
  }

  // Setting up: drop what comes during the quiet time, then ask for replies one at a time
  // until two in a row come back exactly (nine bytes, nothing more, the id) and plausible
  // (each judged against the one before, the first against the preset offsets): a stray
  // byte (a late answer to a frame sent before the reset) would otherwise shift a reply
  // and hand the loop a made-up pose, and a board's absurd angles would become the
  // correction that every later angle carries.
  if (state_ == HaplyLinkState::configuring) {
    ++counters_.unmeasured_polls;
    if (!request_sent_) {
      counters_.bytes_dropped += rx_size_;
      rx_size_ = 0;
      if (now_ns - configured_ns_ < config_.resync_quiet_ns) return;
      send_request(now_ns);
      return;
    }
    if (rx_size_ < kHaplyReplyBytes) {
      if (waiting_since_ns_ >= 0 && now_ns - waiting_since_ns_ > config_.silence_ns) {
        begin_resync(HaplyResyncReason::silence, now_ns);
      }
      return;
    }
    const std::optional<Vec2> board_deg =
        rx_size_ == kHaplyReplyBytes ? decode_reply(setup_, rx_.data()) : std::optional<Vec2>{};
    if (!board_deg) {
      ++counters_.setup_retries;
      restart_setup(now_ns);
      return;
    }
    if (const ReadingFault fault = judge(*board_deg, now_ns); fault != ReadingFault::none) {
      count_implausible(fault, now_ns);
      restart_setup(now_ns);
      return;
    }
    rx_size_ = 0;
    if (!have_candidate_) {
      have_candidate_ = true;
      reference_deg_ = *board_deg;
      reference_ns_ = now_ns;
      send_request(now_ns);
      return;
    }
    accept(*board_deg, now_ns);
    state_ = HaplyLinkState::running;
    status_ = PositionStatus::fresh;
    restart_pending_ = true;
    ever_running_ = true;
    return;
  }

  // Running: whole replies, oldest first; each must carry the id and plausible angles.
  std::size_t used = 0;
  while (rx_size_ - used >= kHaplyReplyBytes) {
    const std::uint8_t* reply = rx_.data() + used;
    const std::optional<Vec2> board_deg = decode_reply(setup_, reply);
    if (!board_deg) return begin_resync(HaplyResyncReason::wrong_id, now_ns);
    if (const ReadingFault fault = judge(*board_deg, now_ns); fault != ReadingFault::none) {
      count_implausible(fault, now_ns);
      return begin_resync(fault == ReadingFault::not_finite ? HaplyResyncReason::corrupt : HaplyResyncReason::jump,
                          now_ns);
    }
    accept(*board_deg, now_ns);
    used += kHaplyReplyBytes;
  }
  if (used > 0) {
    std::memmove(rx_.data(), rx_.data() + used, rx_size_ - used);
    rx_size_ -= used;
    rx_partial_since_ns_ = rx_size_ > 0 ? now_ns : -1;
  } else if (rx_size_ > 0 && rx_partial_since_ns_ < 0) {
    rx_partial_since_ns_ = now_ns;
  }

  // A reply begun and never finished; frames that nobody answers.
  if (rx_partial_since_ns_ >= 0 && now_ns - rx_partial_since_ns_ > config_.short_reply_ns) {
    return begin_resync(HaplyResyncReason::short_reply, now_ns);
  }
  if (waiting_since_ns_ >= 0 && now_ns - waiting_since_ns_ > config_.silence_ns) {
    return begin_resync(HaplyResyncReason::silence, now_ns);
  }

  // How far the angles can be trusted.
  if (state_ != HaplyLinkState::running) {
    if (state_ == HaplyLinkState::configuring) status_ = PositionStatus::unmeasured;
    return;
  }
  if (now_ns - last_reply_ns_ > config_.max_angle_age_ns) {
    status_ = PositionStatus::stale;
    ++counters_.stale_polls;
  } else {
    status_ = PositionStatus::fresh;
  }
}

void HaplyLink::send(const Vec2& joint_torque_N_m, std::int64_t now_ns) noexcept {
  if (state_ != HaplyLinkState::running) return;
  send_frame(encode_torques(setup_, joint_torque_N_m));
  ++outstanding_;
  if (waiting_since_ns_ < 0) waiting_since_ns_ = now_ns;
}

std::string HaplyLink::report(std::int64_t start_ns) const {
  const HaplyLinkCounters& c = counters_;
  std::string text = printf_string("  haply link       %llu frames sent, %llu replies; %llu resyncs",
                                   static_cast<unsigned long long>(c.frames_sent),
                                   static_cast<unsigned long long>(c.replies),
                                   static_cast<unsigned long long>(c.resyncs));
  if (c.resyncs > 0) {
    std::string reasons;
    for (int i = 0; i < kHaplyResyncReasons; ++i) {
      if (c.by_reason[static_cast<std::size_t>(i)] == 0) continue;
      reasons += printf_string("%s%s %llu", reasons.empty() ? "" : ", ",
                               haply_resync_reason_name(static_cast<HaplyResyncReason>(i)),
                               static_cast<unsigned long long>(c.by_reason[static_cast<std::size_t>(i)]));
    }
    text += " (" + reasons + printf_string("), the first at t %.3f s (%s)",
                                           static_cast<double>(c.first_resync_ns - start_ns) * 1e-9,
                                           haply_resync_reason_name(c.first_reason));
  }
  text += printf_string("; %llu frames the port took in part (the rest sent next), %llu dropped whole (queue full)",
                        static_cast<unsigned long long>(c.partial_writes),
                        static_cast<unsigned long long>(c.frames_dropped));
  text += printf_string("\n  position         %llu ticks with no position, %llu with a stale one (older than %.1f ms); "
                        "%llu bytes dropped; %llu setups retried (replies not back exactly twice in a row)\n",
                        static_cast<unsigned long long>(c.unmeasured_polls),
                        static_cast<unsigned long long>(c.stale_polls),
                        static_cast<double>(config_.max_angle_age_ns) * 1e-6,
                        static_cast<unsigned long long>(c.bytes_dropped),
                        static_cast<unsigned long long>(c.setup_retries));
  if (c.implausible > 0) {
    text += printf_string("  implausible      %llu replies rejected, the first at t %.3f s (an angle %s): no torque "
                          "from any of them\n",
                          static_cast<unsigned long long>(c.implausible),
                          static_cast<double>(c.first_implausible_ns - start_ns) * 1e-9,
                          reading_fault_name(c.first_implausible_fault));
  }
  if (c.resyncs > 0 && ever_running_) {
    text += printf_string("  angles           carried across the resyncs by a correction of (%.3f, %.3f) deg: if the "
                          "arm moved while the link was down, stop, put it at its reference pose and start again\n",
                          correction_deg_[0], correction_deg_[1]);
  }
  return text;
}

}  // namespace hapscene
