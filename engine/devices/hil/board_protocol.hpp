#pragma once
// The channel between hapscene and its simulated board process (hapscene-board, see
// simulated_board.hpp): fixed-size messages over a Unix socket, in lock-step. Each request
// carries the sensor reading and the host's bytes for the UART, then asks the board to run
// to a cycle (or to reset); each reply carries the pins, the cycle and the bytes the
// firmware sent. Both ends are the same build on the same machine, so the
// structs go over as they are.
#include <cstddef>
#include <cstdint>

namespace hapscene::board_protocol {

// Host -> board and board -> host byte queues hold this many bytes.
inline constexpr std::size_t kQueueBytes = 4096;
// The board process reads requests on this descriptor and writes replies to it.
inline constexpr int kChannelFd = 3;
// No sensor reading given yet (the ADC input stays at its power-up 0 V).
inline constexpr std::int32_t kNoSensor = INT32_MIN;

enum class Op : std::uint8_t { run_until = 1, reset = 2 };

struct Request {
  Op op{Op::run_until};
  std::uint8_t unused{};
  std::uint16_t byte_count{};      // host bytes following the request
  std::int32_t sensor_counts{kNoSensor};
  std::uint64_t cycle{};           // run_until: the cycle to run to
};

struct Reply {
  std::uint64_t cycle{};
  double motor_duty{};
  std::uint16_t byte_count{};        // board bytes following the reply
  std::uint16_t to_board_pending{};  // host bytes still queued for the UART
  std::uint8_t direction_high{};
  std::uint8_t unused[3]{};
};

}  // namespace hapscene::board_protocol
