// Fuzz target: the host's side of the board protocol (BoardLink over a ByteLink, with the
// shared frame decoder) fed whatever a broken or hostile board could send, tick by tick,
// with the port failing and time jumping now and then; then the run summary's board report.
//
// Input: one mode byte, then per tick a control byte and that tick's bytes.
//   control & 0x3F  bytes arriving this tick (raw mode) or frames (frame mode, 0..3)
//   control & 0x40  the port fails this tick (read and write return -1; reopen succeeds)
//   control & 0x80  100 ms pass before this tick (silence, HELLO retries, reopen)
// Raw mode takes the bytes as they are; frame mode reads (type, seq, length, payload) and
// encodes each as a valid frame, so the fuzzer gets past the CRC to the session's logic.
#include <algorithm>
#include <vector>

#include "engine/devices/board_link.hpp"
#include "engine/devices/board_report.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

using hapscene::fuzz::fuzz_require;

class FuzzedPort final : public hapscene::ByteLink {
 public:
  long read_some(std::uint8_t* data, std::size_t capacity) noexcept override {
    if (failing) return -1;
    const std::size_t n = std::min(capacity, arriving.size() - read_at);
    std::copy_n(arriving.begin() + static_cast<long>(read_at), n, data);
    read_at += n;
    return static_cast<long>(n);
  }
  long write_some(const std::uint8_t* data, std::size_t size) noexcept override {
    if (failing) return -1;
    fuzz_require(size <= HS_MAX_FRAME && data[0] == HS_START_BYTE, "host sent a malformed frame");
    return static_cast<long>(size);
  }
  bool reopen() noexcept override { return !failing; }

  void arrive(const std::uint8_t* data, std::size_t size) {
    arriving.erase(arriving.begin(), arriving.begin() + static_cast<long>(read_at));
    read_at = 0;
    arriving.insert(arriving.end(), data, data + size);
  }

  std::vector<std::uint8_t> arriving;
  std::size_t read_at{};
  bool failing{};
};

// Reads input bytes; zeros past the end.
struct Input {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t at{};
  bool done() const { return at >= size; }
  std::uint8_t next() { return at < size ? data[at++] : 0; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hapscene;
  Input input{data, size};
  const bool frame_mode = (input.next() & 1) != 0;
  FuzzedPort port;
  BoardLinkConfig config;
  BoardLink link(port, config);
  std::int64_t now_ns = 0;
  constexpr std::int64_t kTick_ns = 1'000'000;
  const std::int64_t start_ns = now_ns;
  for (int tick = 0; !input.done() && tick < 4096; ++tick) {
    const std::uint8_t control = input.next();
    if (control & 0x80) now_ns += 100'000'000;
    port.failing = (control & 0x40) != 0;
    const std::size_t count = control & 0x3F;
    if (!frame_mode) {
      const std::size_t n = std::min(count, input.size - input.at);
      port.arrive(input.data + input.at, n);
      input.at += n;
    } else {
      for (std::size_t f = 0; f < count % 4; ++f) {
        // Types: the board's four by index (high bit set), or any byte.
        static constexpr std::uint8_t kBoardTypes[4] = {HS_TYPE_HELLO_REPLY, HS_TYPE_STATE,
                                                        HS_TYPE_STATS, HS_TYPE_REFUSED};
        const std::uint8_t type_byte = input.next();
        const std::uint8_t type = (type_byte & 0x80) ? kBoardTypes[type_byte & 3] : type_byte;
        const std::uint8_t seq = input.next();
        const std::uint8_t length = static_cast<std::uint8_t>(input.next() % (HS_MAX_PAYLOAD + 1));
        std::uint8_t payload[HS_MAX_PAYLOAD]{};
        for (std::uint8_t i = 0; i < length; ++i) payload[i] = input.next();
        std::uint8_t frame[HS_MAX_FRAME];
        const std::uint8_t frame_size = hs_encode_frame(type, seq, payload, length, frame);
        port.arrive(frame, frame_size);
      }
    }
    // One tick as the serial device runs it.
    link.poll(now_ns);
    const double duty = static_cast<double>(tick % 11) / 10.0;
    link.send(MotorCommand{duty, (tick & 1) != 0}, now_ns);
    link.take_restart();
    fuzz_require(link.event_count() <= BoardLink::kMaxEvents, "event list over its size");
    fuzz_require(link.decoder().count <= HS_MAX_FRAME, "decoder buffer over its size");
    now_ns += kTick_ns;
  }
  const std::string report = board_report(link, start_ns);
  fuzz_require(!report.empty(), "empty board report");
  return 0;
}
