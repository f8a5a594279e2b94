#pragma once
// The Hapkit board on simavr: the real firmware .elf running on a simulated ATmega328P
// at 16 MHz, with the board's wiring exposed to the host side of the simulation:
//   UART0     bytes in (paced by simavr at the firmware's baud rate) and out
//   ADC2 (A2) the MR sensor voltage, set in counts of the 10-bit ADC
//   OC0B (D5) the motor PWM duty, read from the timer and port registers
//   PB0 (D8)  the motor direction pin
// Time only moves in run_until(); nothing sleeps, so it runs as fast as the host can.
// simavr's headers stay inside simulated_board.cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace hapscene {

class SimulatedBoard {
 public:
  static constexpr std::uint32_t kClock_Hz = 16'000'000;

  // Loads and boots the firmware. Throws InputError for a missing or unreadable .elf, one
  // that fails check_avr_firmware(), or one that simavr cannot load in a trial boot in a
  // child process (a crash or an abort there is this error, not a crash of hapscene).
  explicit SimulatedBoard(const std::string& firmware_elf);
  ~SimulatedBoard();
  SimulatedBoard(const SimulatedBoard&) = delete;
  SimulatedBoard& operator=(const SimulatedBoard&) = delete;

  // Runs the CPU (timers, interrupts, UART) until `cycle`.
  void run_until(std::uint64_t cycle) noexcept;
  std::uint64_t cycle() const noexcept;
  // Whether the core stopped for good (crashed or ended); a reset revives it.
  bool halted() const noexcept;

  // The MR sensor output as the ADC will convert it (clamped to 0..1023 counts).
  void set_sensor_counts(std::int32_t counts) noexcept;
  // The motor output now: duty in [0, 1] from OC0B or the plain pin, and the direction.
  double motor_duty() const noexcept;
  bool direction_high() const noexcept;

  // Bytes for the board's UART receiver, delivered as its 64-byte FIFO has room.
  // Returns false (byte dropped) when the host-side queue is full.
  bool send_byte(std::uint8_t byte) noexcept;
  // Takes bytes the firmware transmitted; returns how many.
  std::size_t take_bytes(std::uint8_t* out, std::size_t capacity) noexcept;

  // The external reset pin: the CPU restarts from its reset vector.
  void reset() noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hapscene
