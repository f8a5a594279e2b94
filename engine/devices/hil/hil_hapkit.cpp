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
    substep(h_s, /*move_plant=*/false, /*host_receives=*/true);
  }
  if (board_.lost()) throw std::runtime_error("--device hil: " + board_.failure() + " during the handshake");
  if (link_.state() != LinkState::running) {
    throw std::runtime_error("--device hil: the simulated board did not complete the handshake within " +
                             printf_string("%g", config.handshake_timeout_s) + " s: " + handshake_failure(link_) + " (" +
                             config.firmware_elf + " is not the hapscene firmware?)");
  }
  start_cycle_ = board_.cycle();
  substeps_per_tick_ = std::max(10, plant_.config().substeps_per_tick);
}

// Simulated time from the board's cycle counter (62.5 ns per cycle at 16 MHz); the wall
// clock's while the world keeps its pace.
std::int64_t HilHapkit::now_ns() const noexcept {
  if (world_.running()) return paced_from_ns_ + world_.elapsed_ns();
  return board_ns() + after_paced_ns_;
}

void HilHapkit::begin_real_time(double period_s) {
  if (world_.running() || board_.lost()) return;
  paced_from_ns_ = now_ns();
  wire_.set_paced(true);
  world_.start(period_s / substeps_per_tick_);
}

void HilHapkit::end_real_time() noexcept {
  if (!world_.running()) return;
  const std::int64_t host_ns = now_ns();
  world_.stop();
  wire_.set_paced(false);
  after_paced_ns_ = std::max<std::int64_t>(0, host_ns - board_ns());
}

bool HilHapkit::paced_substep(void* self, double h_s) noexcept {
  auto& hil = *static_cast<HilHapkit*>(self);
  hil.wire_.move_to_board();
  hil.substep(h_s, /*move_plant=*/true, /*host_receives=*/false);
  hil.wire_.move_to_host();
  return !hil.board_.lost();
}

std::int32_t HilHapkit::read() noexcept {
  link_.poll(now_ns());
  return link_.counts();
}

void HilHapkit::write(const MotorCommand& command) noexcept { link_.send(command, now_ns()); }

void HilHapkit::advance(double dt_s) noexcept {
  if (world_.running()) return;  // the world keeps its own pace
  // The CPU and the plant meet at least every tenth of a tick (the board samples at 5 kHz),
  // however few steps the plant's integrator needs.
  const double h_s = dt_s / substeps_per_tick_;
  for (int i = 0; i < substeps_per_tick_; ++i) substep(h_s, /*move_plant=*/true, /*host_receives=*/true);
}

void HilHapkit::substep(double h_s, bool move_plant, bool host_receives) noexcept {
  // Sensor in, CPU runs, motor out.
  board_.set_sensor_counts(plant_.sensor_counts());
  const auto cycles = static_cast<std::uint64_t>(std::llround(h_s * SimulatedBoard::kClock_Hz));
  board_.run_until(board_.cycle() + cycles);
  const MotorCommand pins{board_.motor_duty(), board_.direction_high()};
  motor_force_N_ = motor_to_force_N(plant_.profile(), pins);
  if (move_plant) plant_.substep(h_s, motor_force_N_);
  truth_.store(Truth{plant_.x_m(), plant_.v_m_per_s(), motor_force_N_, plant_.hand_force_N(), plant_.hand_target_m()});
  // In lock-step, what the board sent during the substep reaches the host with this
  // timestamp, so the round trip is measured to a substep rather than to a tick. (Paced,
  // the host reads it when its tick comes, as from a real board.)
  if (host_receives) link_.receive(now_ns());
}

std::string HilHapkit::report() const {
  std::string lines = board_report(link_, SimulatedBoard::cycles_to_ns(start_cycle_)) + world_.report();
  if (board_.lost()) {
    lines += "  FAULT            " + board_.failure() + ": zero force commanded, run stopped\n";
  }
  return lines;
}

}  // namespace hapscene
