#pragma once
// The Hapkit board on simavr, as hapscene sees it: the real firmware .elf running on a
// simulated ATmega328P at 16 MHz in a process of its own (hapscene-board, started with
// posix_spawn), with the board's wiring exposed to the host side of the simulation:
//   UART0     bytes in (paced by simavr at the firmware's baud rate) and out
//   ADC2 (A2) the MR sensor voltage, set in counts of the 10-bit ADC
//   OC0B (D5) the motor PWM duty, read from the timer and port registers
//   PB0 (D8)  the motor direction pin
// Time only moves in run_until() and reset(), each one round trip to the board process
// carrying the sensor reading and the host's bytes, and bringing back the pins and the
// board's bytes; the other calls use what the last round trip brought. Nothing sleeps.
//
// A board process that crashes, aborts, hangs (no reply within kReplyTimeout_ms) or
// breaks the channel is lost: it is killed, its pins read zero (no motor force), time
// still passes and nothing runs; lost() says so and failure() says why.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include <sys/types.h>

#include "engine/devices/hil/board_protocol.hpp"

namespace hapscene {

class SimulatedBoard {
 public:
  static constexpr std::uint32_t kClock_Hz = 16'000'000;
  static constexpr int kReplyTimeout_ms = 5000;  // wall clock, per round trip

  // Checks the firmware and starts the board process on it. Throws InputError for a
  // missing or unreadable .elf, one that fails check_avr_firmware(), or one that simavr
  // cannot load or crashes on in the process's 10 ms trial boot; std::runtime_error when
  // the board process cannot be started.
  explicit SimulatedBoard(const std::string& firmware_elf);
  ~SimulatedBoard();
  SimulatedBoard(const SimulatedBoard&) = delete;
  SimulatedBoard& operator=(const SimulatedBoard&) = delete;

  // Runs the CPU (timers, interrupts, UART) until `cycle`.
  void run_until(std::uint64_t cycle) noexcept;
  // The same in two halves, so that several boards compute at once: the request (the
  // board process starts), then its reply (the pins and bytes above change only here).
  void start_run_until(std::uint64_t cycle) noexcept;
  void finish_run() noexcept;
  std::uint64_t cycle() const noexcept { return cycle_; }
  // A count of the 16 MHz clock's cycles as board time: 62.5 ns each.
  static std::int64_t cycles_to_ns(std::uint64_t cycles) noexcept { return static_cast<std::int64_t>(cycles * 125 / 2); }

  // The MR sensor output as the ADC will convert it (clamped to 0..1023 counts).
  void set_sensor_counts(std::int32_t counts) noexcept { sensor_counts_ = counts; }
  // The motor output now: duty in [0, 1] from OC0B or the plain pin, and the direction.
  double motor_duty() const noexcept { return motor_duty_; }
  bool direction_high() const noexcept { return direction_high_; }

  // Bytes for the board's UART receiver, delivered as its 64-byte FIFO has room.
  // Returns false (byte dropped) when the host-side queue is full.
  bool send_byte(std::uint8_t byte) noexcept;
  // Takes bytes the firmware transmitted; returns how many.
  std::size_t take_bytes(std::uint8_t* out, std::size_t capacity) noexcept;

  // The external reset pin: the CPU restarts from its reset vector.
  void reset() noexcept;

  // The board process, and whether and why it was lost (failure() is for after the run:
  // it builds the message).
  pid_t process_id() const noexcept { return child_; }
  bool lost() const noexcept { return lost_; }
  std::string failure() const;

 private:
  enum class Loss : std::uint8_t { none, exited, signalled, timed_out, channel };

  // One round trip, or its halves; false (and the board lost) when the process does not
  // take the request or does not answer.
  bool exchange(board_protocol::Op op, std::uint64_t cycle) noexcept;
  bool send_request(board_protocol::Op op, std::uint64_t cycle) noexcept;
  bool receive_reply() noexcept;
  void lose(Loss why) noexcept;
  std::string said() const;  // what the process wrote on its stderr (simavr's errors)
  mutable std::string said_;

  pid_t child_{-1};
  int channel_{-1};
  int stderr_pipe_{-1};
  std::string firmware_elf_;

  // The state the last reply brought.
  std::uint64_t cycle_{};
  std::uint64_t running_to_{};  // the cycle of the request under way
  double motor_duty_{};
  bool direction_high_{};
  std::size_t to_board_pending_{};  // host bytes queued in the process
  std::int32_t sensor_counts_{board_protocol::kNoSensor};

  // The next request as it is sent: its header, then the host -> board bytes queued for
  // it (to_board_count_ of them); board -> host bytes not yet taken.
  static constexpr std::size_t kRequestHeaderBytes = sizeof(board_protocol::Request);
  std::array<std::uint8_t, kRequestHeaderBytes + board_protocol::kQueueBytes> request_message_{};
  std::size_t to_board_count_{};
  std::array<std::uint8_t, board_protocol::kQueueBytes> to_host_{};
  std::size_t to_host_head_{}, to_host_count_{};
  std::array<std::uint8_t, board_protocol::kQueueBytes> reply_bytes_{};

  // Why the process was lost.
  Loss loss_{Loss::none};
  bool lost_{};
  int wait_status_{};
  std::uint64_t lost_at_cycle_{};
};

}  // namespace hapscene
