// The board protocol (protocol/protocol.h): CRC, frames, payloads, and a decoder
// that counts and skips corrupt and lost frames and resyncs after garbage.
#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

#include "protocol/protocol.h"

namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes frame_bytes(std::uint8_t type, std::uint8_t seq, const Bytes& payload) {
  std::uint8_t out[HS_MAX_FRAME];
  const std::uint8_t size = hs_encode_frame(type, seq, payload.data(),
                                            static_cast<std::uint8_t>(payload.size()), out);
  return Bytes(out, out + size);
}

// Feeds bytes and returns every frame the decoder gives back.
std::vector<hs_frame> decode(hs_decoder* decoder, const Bytes& bytes) {
  std::vector<hs_frame> frames;
  for (std::uint8_t byte : bytes) {
    hs_decoder_push(decoder, byte);
    hs_frame frame;
    while (hs_decoder_poll(decoder, &frame)) frames.push_back(frame);
  }
  return frames;
}

Bytes command_frame(std::uint8_t seq, std::uint8_t duty) {
  return frame_bytes(HS_TYPE_COMMAND, seq, {duty, HS_COMMAND_ENABLE});
}

}  // namespace

TEST_CASE("protocol: CRC-16/CCITT-FALSE matches its check value") {
  const char* text = "123456789";
  CHECK(hs_crc16(reinterpret_cast<const std::uint8_t*>(text), 9) == 0x29B1);
}

TEST_CASE("protocol: a frame has start, type, sequence, length, payload and CRC") {
  const Bytes frame = frame_bytes(HS_TYPE_COMMAND, 7, {200, 3});
  REQUIRE(frame.size() == 8);
  CHECK(frame[0] == 0xA5);
  CHECK(frame[1] == HS_TYPE_COMMAND);
  CHECK(frame[2] == 7);
  CHECK(frame[3] == 2);
  CHECK(frame[4] == 200);
  CHECK(frame[5] == 3);
  CHECK(hs_get_u16(&frame[6]) == hs_crc16(&frame[1], 5));
  std::uint8_t out[HS_MAX_FRAME];
  const std::uint8_t too_long[HS_MAX_PAYLOAD + 1] = {};
  CHECK(hs_encode_frame(HS_TYPE_STATE, 0, too_long, HS_MAX_PAYLOAD + 1, out) == 0);
}

TEST_CASE("protocol: payloads round-trip field by field, little-endian") {
  hs_state state{9, HS_STATUS_ARMED | HS_STATUS_MOTOR_ON, 971, -123456, 65535, 4, 0};
  std::uint8_t bytes[HS_STATE_SIZE];
  hs_put_state(&state, bytes);
  CHECK(bytes[2] == (971 & 0xFF));
  CHECK(bytes[3] == (971 >> 8));
  hs_state back{};
  hs_get_state(bytes, &back);
  CHECK(back.echo_seq == 9);
  CHECK(back.raw_counts == 971);
  CHECK(back.unwrapped_counts == -123456);
  CHECK(back.sample_count == 65535);
  CHECK(back.boot_id == 4);

  hs_hello_reply hello{1, 0, 1, 0, HS_BOARD_HAPKIT3, {0x1E, 0x95, 0x0F}, 5000, 242, 20, 8, 3, 0};
  std::uint8_t hello_bytes[HS_HELLO_REPLY_SIZE];
  hs_put_hello_reply(&hello, hello_bytes);
  hs_hello_reply hello_back{};
  hs_get_hello_reply(hello_bytes, &hello_back);
  CHECK(hello_back.sample_rate_hz == 5000);
  CHECK(hello_back.signature[2] == 0x0F);
  CHECK(hello_back.reset_cause == 8);

  hs_stats stats{1000, 2000, 3, 4, 5, 6, 7, 8};
  std::uint8_t stats_bytes[HS_STATS_SIZE];
  hs_put_stats(&stats, stats_bytes);
  hs_stats stats_back{};
  hs_get_stats(stats_bytes, &stats_back);
  CHECK(stats_back.loop_cycles_max == 2000);
  CHECK(stats_back.length_errors == 8);
}

TEST_CASE("protocol: the decoder returns back-to-back frames") {
  hs_decoder decoder;
  hs_decoder_init(&decoder);
  Bytes stream = command_frame(1, 10);
  const Bytes second = command_frame(2, 20);
  stream.insert(stream.end(), second.begin(), second.end());
  const auto frames = decode(&decoder, stream);
  REQUIRE(frames.size() == 2);
  CHECK(frames[0].seq == 1);
  CHECK(frames[0].payload[0] == 10);
  CHECK(frames[1].payload[0] == 20);
  CHECK(decoder.frames_ok == 2);
  CHECK(decoder.bytes_skipped == 0);
}

TEST_CASE("protocol: garbage before a frame is skipped and counted") {
  hs_decoder decoder;
  hs_decoder_init(&decoder);
  Bytes stream = {0x00, 0xFF, 0x13, 0xA5, 0xA5, 0x42};  // including false start bytes
  const Bytes frame = command_frame(5, 77);
  stream.insert(stream.end(), frame.begin(), frame.end());
  const auto frames = decode(&decoder, stream);
  REQUIRE(frames.size() == 1);
  CHECK(frames[0].payload[0] == 77);
  CHECK(decoder.bytes_skipped == 6);
}

TEST_CASE("protocol: a corrupt byte costs that frame only") {
  hs_decoder decoder;
  hs_decoder_init(&decoder);
  Bytes bad = command_frame(1, 10);
  bad[4] ^= 0x10;  // flipped bit in the payload
  Bytes stream = bad;
  const Bytes good = command_frame(2, 20);
  stream.insert(stream.end(), good.begin(), good.end());
  const auto frames = decode(&decoder, stream);
  REQUIRE(frames.size() == 1);
  CHECK(frames[0].seq == 2);
  CHECK(decoder.crc_errors == 1);
}

TEST_CASE("protocol: a lost byte costs that frame only, even when it swallows the next") {
  hs_decoder decoder;
  hs_decoder_init(&decoder);
  Bytes stream = command_frame(1, 10);
  stream.erase(stream.begin() + 3);  // the length byte is gone: payload read as length
  for (std::uint8_t seq = 2; seq < 6; ++seq) {
    const Bytes next = command_frame(seq, static_cast<std::uint8_t>(seq * 10));
    stream.insert(stream.end(), next.begin(), next.end());
  }
  const auto frames = decode(&decoder, stream);
  REQUIRE(frames.size() == 4);
  CHECK(frames[0].seq == 2);
  CHECK(frames[3].seq == 5);
  CHECK(decoder.crc_errors + decoder.length_errors >= 1);
}

TEST_CASE("protocol: an over-long length is refused without waiting for its bytes") {
  hs_decoder decoder;
  hs_decoder_init(&decoder);
  Bytes stream = {0xA5, HS_TYPE_STATE, 0, 200};
  const Bytes good = command_frame(3, 30);
  stream.insert(stream.end(), good.begin(), good.end());
  const auto frames = decode(&decoder, stream);
  REQUIRE(frames.size() == 1);
  CHECK(frames[0].seq == 3);
  CHECK(decoder.length_errors == 1);
}

TEST_CASE("protocol: random noise never yields a frame and never overflows the buffer") {
  hs_decoder decoder;
  hs_decoder_init(&decoder);
  std::uint32_t x = 12345;
  Bytes noise;
  for (int i = 0; i < 20000; ++i) {
    x = x * 1664525u + 1013904223u;
    noise.push_back(static_cast<std::uint8_t>(x >> 24));
  }
  const auto frames = decode(&decoder, noise);
  CHECK(frames.size() <= 1);  // a chance match needs a 16-bit CRC hit
  CHECK(decoder.count <= HS_MAX_FRAME);
  // And it still decodes a real frame afterwards (a pending false start may eat one).
  Bytes tail;
  for (std::uint8_t seq = 0; seq < 3; ++seq) {
    const Bytes frame = command_frame(seq, 1);
    tail.insert(tail.end(), frame.begin(), frame.end());
  }
  CHECK(decode(&decoder, tail).size() >= 2);
}
