#pragma once
// A stand-in for a board running Haply's stock firmware, written from the protocol's
// description (engine/devices/haply/haply_protocol.hpp): it parses the host's bytes as the
// firmware does (a command byte, then as many bytes as that command takes), keeps the
// torques until the next command (no timeout), presets its encoders at setup and answers
// each torque frame with the id and an angle per encoder port. Faults on demand: garbage,
// short replies, wrong ids, silence, a reset (encoder counts back at their preset), and
// replies whose angles are whatever the test says (3e17 deg, NaN, a jump).
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/devices/byte_link.hpp"
#include "engine/devices/haply/haply_protocol.hpp"

namespace hapscene::test {

class FakeHaplyBoard {
 public:
  // The host's bytes in; the board's answers appended to `out`.
  void receive(const std::uint8_t* data, std::size_t size, std::vector<std::uint8_t>* out) {
    for (std::size_t i = 0; i < size; ++i) push(data[i], out);
  }

  // The arm: turns the joint on `port` (1..4) by `deg`, as its encoder counts it.
  void turn(int port, double deg) { counts_[index(port)] += deg * cpr_[index(port)] / 360.0; }
  double angle_deg(int port) const { return cpr_[index(port)] > 0 ? 360.0 * std::floor(counts_[index(port)]) / cpr_[index(port)] : 0.0; }
  // A board reset (a brown-out): the encoders read their setup offsets again.
  void reset_counts() {
    for (std::size_t p = 0; p < 4; ++p) counts_[p] = offset_deg_[p] * cpr_[p] / 360.0;
  }

  // Faults.
  bool muted{false};                 // reads and applies, answers nothing
  int short_replies{0};              // the next n replies lose their last 3 bytes
  bool mute_after_reply{false};      // after the next reply, mute
  int wrong_ids{0};                  // the next n replies carry id + 1
  std::vector<std::uint8_t> garbage; // sent before the next reply, once
  int forced_replies{0};             // the next n replies report forced_deg on every port
  float forced_deg{0.0f};

  // What the board saw.
  int resets{0}, setups{0}, torque_frames{0};
  std::uint8_t id{0};
  std::uint8_t motor_mask{0}, encoder_mask{0};
  std::array<std::uint8_t, 4> motor_direction{}, encoder_direction{};
  std::array<float, 4> torque_N_m{};  // per port, as last applied
  float peak_torque_N_m{0.0f};        // the largest |torque| ever applied
  int torque_since_reset{0};          // torque frames with a non-zero torque since the last reset command
  std::array<double, 4> offset_deg_{}, cpr_{};

 private:
  static std::size_t index(int port) { return static_cast<std::size_t>(port - 1); }
  static int bits(std::uint8_t mask) { return std::popcount(mask); }

  // How many bytes the frame begun in `frame_` takes in all, once enough of it is known.
  std::size_t frame_length() const {
    const std::uint8_t command = frame_[0];
    if (command == 0) return 2;
    if (command == 2) return 2 + pwm_count_ + 4u * static_cast<std::size_t>(bits(motor_mask));
    // setup: 01 id mmask mdir.. emask edir.. nsensors pins.. npwm pins.. floats
    std::size_t n = 3;
    if (frame_.size() < n) return n + 1;
    n += static_cast<std::size_t>(bits(frame_[2]));
    if (frame_.size() <= n) return n + 1;
    const std::uint8_t emask = frame_[n];
    n += 1 + static_cast<std::size_t>(bits(emask));
    if (frame_.size() <= n) return n + 1;
    n += 1 + frame_[n];  // analog sensors and their pins
    if (frame_.size() <= n) return n + 1;
    n += 1 + frame_[n];  // PWM outputs and their pins
    return n + 8u * static_cast<std::size_t>(bits(emask));
  }

  void push(std::uint8_t byte, std::vector<std::uint8_t>* out) {
    if (frame_.empty() && byte > 2) return;  // not a command: skipped
    frame_.push_back(byte);
    if (frame_.size() < 2 || frame_.size() < frame_length()) return;
    const std::vector<std::uint8_t> frame = std::move(frame_);
    frame_.clear();
    if (frame[0] == 0) on_reset();
    else if (frame[0] == 1) on_setup(frame);
    else on_torques(frame, out);
  }

  void on_reset() {
    ++resets;
    torque_since_reset = 0;
    torque_N_m = {};
    motor_mask = encoder_mask = 0;
    pwm_count_ = 0;
  }

  void on_setup(const std::vector<std::uint8_t>& f) {
    ++setups;
    id = f[1];
    std::size_t n = 2;
    motor_mask = f[n++];
    for (int port = 1; port <= 4; ++port) {
      if (motor_mask & (1u << (port - 1))) motor_direction[index(port)] = f[n++];
    }
    encoder_mask = f[n++];
    for (int port = 1; port <= 4; ++port) {
      if (encoder_mask & (1u << (port - 1))) encoder_direction[index(port)] = f[n++];
    }
    n += 1 + f[n];
    pwm_count_ = f[n];
    n += 1 + f[n];
    for (int port = 1; port <= 4; ++port) {
      if (!(encoder_mask & (1u << (port - 1)))) continue;
      offset_deg_[index(port)] = get_float_le(&f[n]);
      cpr_[index(port)] = get_float_le(&f[n + 4]);
      n += 8;
    }
    reset_counts();
  }

  void on_torques(const std::vector<std::uint8_t>& f, std::vector<std::uint8_t>* out) {
    ++torque_frames;
    std::size_t n = 2 + pwm_count_;
    for (int port = 1; port <= 4; ++port) {
      if (!(motor_mask & (1u << (port - 1)))) continue;
      torque_N_m[index(port)] = std::fmax(-0.123f, std::fmin(0.123f, get_float_le(&f[n])));
      peak_torque_N_m = std::fmax(peak_torque_N_m, std::fabs(torque_N_m[index(port)]));
      n += 4;
    }
    if (torque_N_m != std::array<float, 4>{}) ++torque_since_reset;
    if (muted) return;
    out->insert(out->end(), garbage.begin(), garbage.end());
    garbage.clear();
    std::vector<std::uint8_t> reply{static_cast<std::uint8_t>(wrong_ids > 0 ? f[1] + 1 : f[1])};
    if (wrong_ids > 0) --wrong_ids;
    for (int port = 1; port <= 4; ++port) {
      if (!(encoder_mask & (1u << (port - 1)))) continue;
      std::uint8_t bytes[4];
      put_float_le(forced_replies > 0 ? forced_deg : static_cast<float>(angle_deg(port)), bytes);
      reply.insert(reply.end(), bytes, bytes + 4);
    }
    if (forced_replies > 0) --forced_replies;
    if (short_replies > 0) {
      --short_replies;
      reply.resize(reply.size() - 3);
    }
    out->insert(out->end(), reply.begin(), reply.end());
    if (mute_after_reply) {
      mute_after_reply = false;
      muted = true;
    }
  }

  std::vector<std::uint8_t> frame_;
  std::size_t pwm_count_{0};
  std::array<double, 4> counts_{};
};

// The host's end of an in-memory wire to a FakeHaplyBoard (no threads: what the host
// writes is answered at once; the answers wait until the host reads).
class FakeHaplyWire final : public ByteLink {
 public:
  explicit FakeHaplyWire(FakeHaplyBoard* board) : board_(board) {}
  long read_some(std::uint8_t* data, std::size_t capacity) noexcept override {
    if (unplugged) return -1;
    const std::size_t n = std::min(capacity, to_host_.size() - read_);
    std::copy(to_host_.begin() + static_cast<long>(read_), to_host_.begin() + static_cast<long>(read_ + n), data);
    read_ += n;
    if (read_ == to_host_.size()) {
      to_host_.clear();
      read_ = 0;
    }
    return static_cast<long>(n);
  }
  long write_some(const std::uint8_t* data, std::size_t size) noexcept override {
    if (unplugged) return -1;
    if (takes_at_most >= 0) size = std::min(size, static_cast<std::size_t>(takes_at_most));
    board_->receive(data, size, &to_host_);
    written.insert(written.end(), data, data + size);
    return static_cast<long>(size);
  }
  bool reopen() noexcept override { return !unplugged; }

  bool unplugged{false};
  long takes_at_most{-1};             // >= 0: a port that takes at most this many bytes a write
  std::vector<std::uint8_t> written;  // every byte the host sent

 private:
  FakeHaplyBoard* board_;
  std::vector<std::uint8_t> to_host_;
  std::size_t read_{0};
};

}  // namespace hapscene::test
