#pragma once
// The Hapkit board on simavr, inside the board process (hapscene-board): the real
// firmware .elf on a simulated ATmega328P at 16 MHz, with the board's wiring:
//   UART0     bytes in (paced by simavr at the firmware's baud rate) and out
//   ADC2 (A2) the MR sensor voltage, set in counts of the 10-bit ADC
//   OC0B (D5) the motor PWM duty, read from the timer and port registers
//   PB0 (D8)  the motor direction pin
// Time only moves in run_until(); nothing sleeps. hapscene itself never links simavr:
// it talks to this through SimulatedBoard (../simulated_board.hpp).
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

namespace hapscene {

// Loads `firmware_elf` on a throwaway core and runs 10 ms of it, so that a firmware simavr
// cannot take ends the process while it is still loading. False: not a readable image.
bool simavr_trial_boot(const std::string& firmware_elf);

class SimavrBoard {
 public:
  static constexpr std::uint32_t kClock_Hz = 16'000'000;

  // Loads and boots the firmware; std::runtime_error when simavr cannot read it.
  explicit SimavrBoard(const std::string& firmware_elf);
  ~SimavrBoard();
  SimavrBoard(const SimavrBoard&) = delete;
  SimavrBoard& operator=(const SimavrBoard&) = delete;

  void run_until(std::uint64_t cycle) noexcept;
  std::uint64_t cycle() const noexcept;
  void set_sensor_counts(std::int32_t counts) noexcept;
  double motor_duty() const noexcept;
  bool direction_high() const noexcept;
  bool send_byte(std::uint8_t byte) noexcept;
  std::size_t take_bytes(std::uint8_t* out, std::size_t capacity) noexcept;
  std::size_t to_board_pending() const noexcept;
  void reset() noexcept;

  // Test hook: the process aborts when the core reaches this cycle.
  std::uint64_t abort_at_cycle{std::numeric_limits<std::uint64_t>::max()};

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hapscene
