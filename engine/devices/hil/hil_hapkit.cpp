#include "engine/devices/hil/hil_hapkit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/base/format.hpp"
#include "engine/devices/board_report.hpp"
#include "engine/devices/kinematics.hpp"

namespace hapscene {
HilHapkit::HilHapkit(const DeviceProfile& profile, const HilConfig& config)
    : plant_(profile, config.simulation),
      board_(config.firmware_elf),
      wire_(board_),
      link_(wire_, link_config_for(config.link, profile)) {
  // Power-up with the handle still: HELLO until the board answers.
  board_.set_sensor_counts(plant_.sensor_counts());
  const double h_s = 1e-4;
  const int attempts = static_cast<int>(config.handshake_timeout_s / h_s);
  for (int i = 0; i < attempts && link_.state() != LinkState::running; ++i) {
    link_.send(MotorCommand{}, now_ns());
    substep(h_s, /*move_plant=*/false);
  }
  if (board_.lost()) throw std::runtime_error("--device hil: " + board_.failure() + " during the handshake");
  if (link_.state() != LinkState::running) {
    throw std::runtime_error("--device hil: the simulated board did not complete the handshake within " +
                             printf_string("%g", config.handshake_timeout_s) + " s: " + handshake_failure(link_) + " (" +
                             config.firmware_elf + " is not the hapscene firmware?)");
  }
  start_cycle_ = board_.cycle();
}

// Simulated time from the board's cycle counter (62.5 ns per cycle at 16 MHz).
std::int64_t HilHapkit::now_ns() const noexcept {
  return static_cast<std::int64_t>(board_.cycle() * 125 / 2);
}

std::int32_t HilHapkit::read() noexcept {
  link_.poll(now_ns());
  return link_.counts();
}

void HilHapkit::write(const MotorCommand& command) noexcept { link_.send(command, now_ns()); }

void HilHapkit::advance(double dt_s) noexcept {
  // The CPU and the plant meet at least every tenth of a tick (the board samples at 5 kHz),
  // however few steps the plant's integrator needs.
  const int substeps = std::max(10, plant_.config().substeps_per_tick);
  const double h_s = dt_s / substeps;
  for (int i = 0; i < substeps; ++i) substep(h_s, /*move_plant=*/true);
}

void HilHapkit::substep(double h_s, bool move_plant) noexcept {
  // Sensor in, CPU runs, motor out.
  board_.set_sensor_counts(plant_.sensor_counts());
  const auto cycles = static_cast<std::uint64_t>(std::llround(h_s * SimulatedBoard::kClock_Hz));
  board_.run_until(board_.cycle() + cycles);
  const MotorCommand pins{board_.motor_duty(), board_.direction_high()};
  motor_force_N_ = motor_to_force_N(plant_.profile(), pins);
  if (move_plant) plant_.substep(h_s, motor_force_N_);
  // What the board sent during the substep reaches the host with this timestamp, so the
  // round trip is measured to a substep rather than to a tick.
  link_.receive(now_ns());
}

std::string HilHapkit::report() const {
  std::string lines = board_report(link_, static_cast<std::int64_t>(start_cycle_ * 125 / 2));
  if (board_.lost()) {
    lines += "  FAULT            " + board_.failure() + ": zero force commanded, run stopped\n";
  }
  return lines;
}

}  // namespace hapscene
