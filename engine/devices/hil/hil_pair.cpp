#include "engine/devices/hil/hil_pair.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/base/format.hpp"
#include "engine/devices/board_report.hpp"
#include "engine/devices/planar/simulated_planar.hpp"

namespace hapscene {
namespace {

const char* kHilPairWhat = "--device hil";

PlanarModel checked_model(const PlanarProfile& profile) {
  require_hapkit_joints(profile, kHilPairWhat);
  return compile_planar_model(profile);
}

}  // namespace

HilPair::HilPair(const PlanarProfile& profile, const HilPairConfig& config)
    : model_(checked_model(profile)),
      plant_(planar_plant_parameters(profile), config.simulation),
      joints_{Joint(config.firmware_elf, joint_link_config(config.link, profile, 0)),
              Joint(config.firmware_elf, joint_link_config(config.link, profile, 1))},
      pair_(joints_[0].link, joints_[1].link) {
  // Power-up with the handle still: HELLO to both boards until both answer.
  const double h_s = 1e-4;
  const int attempts = static_cast<int>(config.handshake_timeout_s / h_s);
  for (int i = 0; i < attempts; ++i) {
    if (joints_[0].link.state() == LinkState::running && joints_[1].link.state() == LinkState::running) break;
    for (Joint& joint : joints_) joint.link.send(MotorCommand{}, now_ns());
    substep(h_s, /*move_plant=*/false);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string which = std::string(kHilPairWhat) + ": joint " + std::to_string(i + 1) + "'s simulated board: ";
    if (joints_[i].board.lost()) throw std::runtime_error(which + joints_[i].board.failure() + " during the handshake");
    if (joints_[i].link.state() != LinkState::running) {
      throw std::runtime_error(which + "no handshake within " + printf_string("%g", config.handshake_timeout_s) +
                               " s: " + handshake_failure(joints_[i].link) + " (" + config.firmware_elf +
                               " is not the hapscene firmware?)");
    }
  }
  // The run's own soft start covers the first contact.
  (void)joints_[0].link.take_restart();
  (void)joints_[1].link.take_restart();
  start_cycle_ = joints_[0].board.cycle();
}

HilPair::~HilPair() {
  pair_.send_zero(now_ns());
  // Let the zero commands reach the boards (a tenth of a millisecond of board time).
  substep(1e-4, /*move_plant=*/false);
}

// Simulated time from joint 1's board's cycle counter (62.5 ns per cycle at 16 MHz); both
// boards run to the same cycle.
std::int64_t HilPair::now_ns() const noexcept {
  return SimulatedBoard::cycles_to_ns(joints_[0].board.cycle());
}

PlanarReading HilPair::read() noexcept { return pair_.read(now_ns()); }

void HilPair::write(const PlanarMotorCommand& command) noexcept { pair_.write(command, now_ns()); }

void HilPair::advance(double dt_s) noexcept {
  // The CPUs and the plant meet at least every tenth of a tick (the boards sample at 5 kHz),
  // however few steps the plant's integrator needs.
  const int substeps = std::max(10, plant_.config().substeps_per_tick);
  const double h_s = dt_s / substeps;
  for (int i = 0; i < substeps; ++i) substep(h_s, /*move_plant=*/true);
}

void HilPair::substep(double h_s, bool move_plant) noexcept {
  // Sensors in (each joint's angle as its MR sensor's counts), both CPUs to the same cycle.
  const PlanarReading sensed = planar_reading_for(model_, plant_.q_rad());
  const auto cycles = static_cast<std::uint64_t>(std::llround(h_s * SimulatedBoard::kClock_Hz));
  const std::uint64_t until = joints_[0].board.cycle() + cycles;
  // Both processes compute at once (a core each when there are two), then both answer.
  for (std::size_t i = 0; i < 2; ++i) {
    joints_[i].board.set_sensor_counts(sensed.counts[i]);
    joints_[i].board.start_run_until(until);
  }
  PlanarMotorCommand pins;
  for (std::size_t i = 0; i < 2; ++i) {
    SimulatedBoard& board = joints_[i].board;
    board.finish_run();
    pins.motor[i] = MotorCommand{board.motor_duty(), board.direction_high()};
  }
  // Motors out: the pins through each joint's drive law, then the coupling.
  joint_torque_N_m_ = joint_torques_from_motor_N_m(model_, planar_command_torques_N_m(model_, pins));
  plant_.hold_motor_torques(joint_torque_N_m_);
  if (move_plant) plant_.substep(h_s);
  // What each board sent during the substep reaches the host with this timestamp.
  const std::int64_t now = now_ns();
  for (Joint& joint : joints_) joint.link.receive(now);
}

Vec2 HilPair::motor_force_N() const noexcept {
  return handle_force_from_joint_torques_N(plant_.pose().jacobian, joint_torque_N_m_);
}

std::string HilPair::report() const {
  std::string lines = pair_.report({"simulated board 1", "simulated board 2"},
                                   SimulatedBoard::cycles_to_ns(start_cycle_));
  for (std::size_t i = 0; i < 2; ++i) {
    if (joints_[i].board.lost()) {
      lines += "  FAULT            joint " + std::to_string(i + 1) + "'s board: " + joints_[i].board.failure() +
               ": zero force commanded, run stopped\n";
    }
  }
  return lines;
}

}  // namespace hapscene
