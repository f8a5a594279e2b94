// Fuzz target: the board's frame decoder (protocol/protocol.h, the firmware's own C
// code compiled for the host) on any byte stream, polled after every byte or only now and
// then (a full buffer then drops its oldest byte). Every frame it returns must be a valid
// frame that occurs in the input as it is, and must survive a re-encode unchanged.
#include <cstring>

#include "protocol/protocol.h"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

using hapscene::fuzz::fuzz_require;

void check_frame(const hs_frame& frame, const std::uint8_t* input, std::size_t size) {
  fuzz_require(frame.length <= HS_MAX_PAYLOAD, "decoded payload longer than the maximum");
  std::uint8_t encoded[HS_MAX_FRAME];
  const std::uint8_t encoded_size =
      hs_encode_frame(frame.type, frame.seq, frame.payload, frame.length, encoded);
  fuzz_require(encoded_size == HS_HEADER_SIZE + frame.length + HS_CRC_SIZE, "re-encoded size");
  fuzz_require(::memmem(input, size, encoded, encoded_size) != nullptr,
               "decoded a frame that is not in the input");
  // The re-encoded frame decodes to itself.
  hs_decoder again;
  hs_decoder_init(&again);
  hs_frame decoded{};
  int frames = 0;
  for (std::uint8_t i = 0; i < encoded_size; ++i) {
    hs_decoder_push(&again, encoded[i]);
    while (hs_decoder_poll(&again, &decoded)) ++frames;
  }
  fuzz_require(frames == 1 && decoded.type == frame.type && decoded.seq == frame.seq &&
                   decoded.length == frame.length &&
                   std::memcmp(decoded.payload, frame.payload, frame.length) == 0,
               "a re-encoded frame does not decode to itself");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte: poll after every byte (as the firmware does) or every few bytes.
  const std::size_t poll_every = 1 + data[0] % 8;
  const std::uint8_t* input = data + 1;
  const std::size_t input_size = size - 1;
  hs_decoder decoder;
  hs_decoder_init(&decoder);
  std::size_t frames = 0;
  for (std::size_t i = 0; i < input_size; ++i) {
    hs_decoder_push(&decoder, input[i]);
    fuzz_require(decoder.count <= HS_MAX_FRAME, "decoder buffer over its size");
    if ((i + 1) % poll_every != 0 && i + 1 != input_size) continue;
    hs_frame frame{};
    while (hs_decoder_poll(&decoder, &frame)) {
      check_frame(frame, input, input_size);
      ++frames;
    }
    fuzz_require(decoder.count <= HS_MAX_FRAME, "decoder buffer over its size");
  }
  fuzz_require(frames == 0 || frames * (HS_HEADER_SIZE + HS_CRC_SIZE) <= input_size,
               "more frames than the input can hold");
  fuzz_require(static_cast<std::uint16_t>(frames) == decoder.frames_ok, "frames_ok miscounted");
  return 0;
}
