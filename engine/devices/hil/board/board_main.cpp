// hapscene-board: the simulated Hapkit board in a process of its own, so that a firmware
// that makes simavr crash, abort or hang ends this process, never hapscene. Started by
// SimulatedBoard (posix_spawn) with the firmware path as its argument and the channel on
// descriptor 3; serves requests in lock-step until the channel closes.
//
// Exit codes: 0 channel closed, 2 usage, 3 not a readable AVR firmware image, 4 simavr
// has no ATmega328P core, 5 the channel broke. Test hook: HAPSCENE_BOARD_ABORT_AT_CYCLE=N
// makes the process abort when the board reaches cycle N.
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "engine/base/whole_number.hpp"
#include "engine/devices/hil/board/simavr_board.hpp"
#include "engine/devices/hil/channel_io.hpp"
#include "engine/devices/hil/board_protocol.hpp"

namespace {

using namespace hapscene;
using namespace hapscene::board_protocol;

constexpr unsigned kLoadSeconds = 10;  // wall-clock bound on loading and the trial boot

// hapscene's next request: no time limit (hapscene may pause between runs; it closes
// the channel when it is done).
bool read_exactly(void* data, std::size_t size) {
  return board_channel::read_exactly(kChannelFd, data, size, /*timeout_ms=*/-1, nullptr, /*spin_reads=*/0);
}


// The pins, the cycle and the bytes the firmware sent since the last reply.
bool send_reply(SimavrBoard& board) {
  static std::uint8_t bytes[kQueueBytes];
  Reply reply;
  reply.cycle = board.cycle();
  reply.motor_duty = board.motor_duty();
  reply.direction_high = board.direction_high() ? 1 : 0;
  reply.byte_count = static_cast<std::uint16_t>(board.take_bytes(bytes, sizeof bytes));
  reply.to_board_pending = static_cast<std::uint16_t>(board.to_board_pending());
  static std::uint8_t message[sizeof(Reply) + kQueueBytes];
  std::memcpy(message, &reply, sizeof reply);
  std::memcpy(message + sizeof reply, bytes, reply.byte_count);
  return board_channel::write_exactly(kChannelFd, message, sizeof reply + reply.byte_count);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: hapscene-board FIRMWARE.elf (started by hapscene --device hil)\n");
    return 2;
  }
  const std::string firmware_elf = argv[1];
  // Ctrl-C reaches the whole process group: hapscene stops its run cleanly and then
  // closes the channel, which ends this process; dying of the SIGINT first would make a
  // clean stop look like a lost board.
  signal(SIGINT, SIG_IGN);
  alarm(kLoadSeconds);
  if (!simavr_trial_boot(firmware_elf)) return 3;
  try {
    SimavrBoard board(firmware_elf);
    alarm(0);
    if (const char* abort_at = std::getenv("HAPSCENE_BOARD_ABORT_AT_CYCLE")) {
      // Read whole: "8000000x" or "" must not become an abort at some other cycle.
      if (read_whole_number(abort_at, &board.abort_at_cycle) != WholeNumberRead::ok) {
        std::fprintf(stderr, "HAPSCENE_BOARD_ABORT_AT_CYCLE: expected a whole number of cycles, got \"%s\"\n",
                     abort_at);
        return 2;
      }
    }
    if (!send_reply(board)) return 5;
    // Lock-step: sensor and host bytes in, run or reset, pins and board bytes out.
    static std::uint8_t bytes[kQueueBytes];
    for (;;) {
      Request request;
      if (!read_exactly(&request, sizeof request)) return 0;  // hapscene closed the channel
      if (request.byte_count > sizeof bytes || !read_exactly(bytes, request.byte_count)) return 5;
      if (request.sensor_counts != kNoSensor) board.set_sensor_counts(request.sensor_counts);
      for (std::size_t i = 0; i < request.byte_count; ++i) board.send_byte(bytes[i]);
      if (request.op == Op::reset) {
        board.reset();
      } else {
        board.run_until(request.cycle);
      }
      if (!send_reply(board)) return 5;
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return std::strstr(error.what(), "atmega328p") != nullptr ? 4 : 3;
  }
}
