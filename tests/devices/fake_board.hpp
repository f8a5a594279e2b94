#pragma once
// A stand-in for the Hapkit firmware, for host-side tests: it decodes the host's frames
// and answers as the firmware does (HELLO -> HELLO_REPLY, COMMAND -> STATE or REFUSED
// when not armed, STATS_REQUEST -> STATS). It can go mute or "reset".
#include <cstdint>
#include <vector>

#include <algorithm>

#include "engine/devices/byte_link.hpp"
#include "protocol/protocol.h"

namespace hapscene::test {

class FakeBoard {
 public:
  FakeBoard() { hs_decoder_init(&decoder_); }

  // Bytes from the host in; the answers are appended to `out`.
  void receive(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>* out) {
    for (std::size_t i = 0; i < size; ++i) {
      hs_decoder_push(&decoder_, data[i]);
      hs_frame frame;
      while (hs_decoder_poll(&decoder_, &frame)) on_frame(frame, out);
    }
  }

  // The board's view.
  std::int32_t unwrapped_counts{500};
  bool muted{false};
  bool armed{false};
  bool states_muted{false};   // answer COMMANDs with STATS: alive, but no position
  std::uint8_t protocol_version{HS_PROTOCOL_VERSION};
  int raw_counts_override{-1};  // >= 0: the raw count sent in STATEs
  std::uint8_t extra_status{0};  // flags added to every STATE's status
  int hellos{0};
  int commands{0};
  hs_command last_command{};
  std::uint8_t boot_id{1};

  // A reset: disarmed, sequence and flip count start again.
  void reset(std::int32_t counts_after) {
    armed = false;
    tx_seq_ = 0;
    unwrapped_counts = counts_after;
    ++boot_id;
  }

  const hs_decoder& decoder() const { return decoder_; }

 private:
  void send(std::uint8_t type, const std::uint8_t* payload, std::uint8_t length,
            std::vector<std::uint8_t>* out) {
    std::uint8_t frame[HS_MAX_FRAME];
    const std::uint8_t size = hs_encode_frame(type, tx_seq_++, payload, length, frame);
    out->insert(out->end(), frame, frame + size);
  }

  void on_frame(const hs_frame& frame, std::vector<std::uint8_t>* out) {
    if (muted) return;
    if (frame.type == HS_TYPE_HELLO) {
      ++hellos;
      armed = true;
      hs_hello_reply reply{protocol_version, 0, 1, 0, HS_BOARD_HAPKIT3, {0x1E, 0x95, 0x0F},
                           5000, 242, 20, 1, boot_id, 0};
      std::uint8_t payload[HS_HELLO_REPLY_SIZE];
      hs_put_hello_reply(&reply, payload);
      send(HS_TYPE_HELLO_REPLY, payload, HS_HELLO_REPLY_SIZE, out);
    } else if (frame.type == HS_TYPE_COMMAND) {
      if (!armed) {
        const std::uint8_t payload[2] = {HS_TYPE_COMMAND, HS_REFUSED_NOT_ARMED};
        send(HS_TYPE_REFUSED, payload, 2, out);
        return;
      }
      ++commands;
      hs_get_command(frame.payload, &last_command);
      if (states_muted) {
        hs_stats stats{300, 1500, decoder_.frames_ok, 0, 0, 0, 0, 0};
        std::uint8_t payload[HS_STATS_SIZE];
        hs_put_stats(&stats, payload);
        send(HS_TYPE_STATS, payload, HS_STATS_SIZE, out);
        return;
      }
      const auto raw = static_cast<std::uint16_t>(raw_counts_override >= 0 ? raw_counts_override
                                                                           : (unwrapped_counts & 1023));
      hs_state state{frame.seq, static_cast<std::uint8_t>(HS_STATUS_ARMED | extra_status), raw,
                     unwrapped_counts, 0, boot_id, 0};
      std::uint8_t payload[HS_STATE_SIZE];
      hs_put_state(&state, payload);
      send(HS_TYPE_STATE, payload, HS_STATE_SIZE, out);
    } else if (frame.type == HS_TYPE_STATS_REQUEST) {
      hs_stats stats{300, 1500, decoder_.frames_ok, 0, 0, 0, 0, 0};
      std::uint8_t payload[HS_STATS_SIZE];
      hs_put_stats(&stats, payload);
      send(HS_TYPE_STATS, payload, HS_STATS_SIZE, out);
    }
  }

  hs_decoder decoder_{};
  std::uint8_t tx_seq_{};
};

// An in-memory wire to a FakeBoard; the board's answers arrive at the next read.
class LoopbackLink final : public ByteLink {
 public:
  long read_some(std::uint8_t* data, std::size_t capacity) noexcept override {
    if (gone) return -1;
    const std::size_t n = std::min(capacity, to_host.size());
    std::copy_n(to_host.begin(), n, data);
    to_host.erase(to_host.begin(), to_host.begin() + static_cast<long>(n));
    return static_cast<long>(n);
  }
  long write_some(const std::uint8_t* data, std::size_t size) noexcept override {
    if (gone) return -1;
    if (short_writes && size > 1) --size;  // the port takes all but the last byte
    board.receive(data, size, &to_host);
    return static_cast<long>(size);
  }
  bool reopen() noexcept override {
    ++reopen_attempts;
    if (!can_reopen) return false;
    gone = false;
    return true;
  }

  FakeBoard board;
  std::vector<std::uint8_t> to_host;
  bool gone{false};
  bool can_reopen{false};
  bool short_writes{false};
  int reopen_attempts{0};
};

}  // namespace hapscene::test
