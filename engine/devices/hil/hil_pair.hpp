#pragma once
// Firmware-in-the-loop for a 2-DOF scene (`--device hil` on a Hapkit pantograph): two
// simulated boards, each the real hapscene firmware on simavr's ATmega328P, as joint 1's
// and joint 2's board of the profile, wired to the simulated planar plant, in lock-step.
//
// advance(dt) runs both CPUs for dt worth of cycles in substeps (at least ten a tick);
// at each substep each joint's angle becomes its MR sensor voltage on that board's ADC2,
// both CPUs run to the same cycle, and the PWM duty and direction pin each leaves become
// its motor's torque, which moves the plant. The host reads both boards over their own
// simulated UARTs through the same BoardPair as two real boards (board_pair.hpp), so it
// sees their latency, quantization and faults, and a fault on either board takes both
// motors to zero. Deterministic: the same inputs give the same run.
//
// Lock-step in real time too (unlike the 1-DOF HilHapkit, whose world keeps its own pace
// beside the loop): two boards need more CPU than the simulated time they cover on a
// 2-core machine (2.7 s for 2 s here), so paced they would only fall ever further behind;
// in lock-step the loop's wait for them is counted as the simulation's time.
#include <array>
#include <cstdint>
#include <string>

#include "engine/devices/board_link.hpp"
#include "engine/devices/device.hpp"
#include "engine/devices/hil/simulated_board.hpp"
#include "engine/devices/hil/wire.hpp"
#include "engine/devices/planar/board_pair.hpp"
#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/planar/planar_plant.hpp"
#include "engine/devices/planar/planar_tick.hpp"
#include "engine/devices/planar/planar_profile.hpp"

namespace hapscene {

struct HilPairConfig {
  PlanarSimulationConfig simulation;
  std::string firmware_elf;  // both boards run it
  BoardLinkConfig link{.silence_timeout_ns = 50'000'000,
                       .hello_retry_ns = 5'000'000,
                       .reopen_retry_ns = 500'000'000,
                       .stats_period_ns = 100'000'000};
  double handshake_timeout_s{0.5};  // simulated time
};

class HilPair final : public DeviceOf<2>, public SimulationTruthOf<2> {
 public:
  // InputError: a profile whose joints are not Hapkit boards (MR sensor, duty drive), a
  // missing or damaged firmware; std::runtime_error: a board that does not complete the
  // handshake (the message names the joint).
  HilPair(const PlanarProfile& profile, const HilPairConfig& config);
  // Commands zero force on both motors on the way out.
  ~HilPair() override;

  PlanarReading read() noexcept override;
  void write(const PlanarMotorCommand& command) noexcept override;
  void advance(double dt_s) noexcept override;
  bool take_restart() noexcept override { return pair_.take_restart(); }
  PositionStatus position_status() const noexcept override { return pair_.position_status(); }
  bool fault_seen() const noexcept override { return pair_.fault_seen() || lost(); }
  bool lost() const noexcept override { return joints_[0].board.lost() || joints_[1].board.lost(); }
  std::string report() const override;
  void link_health(DeviceLinkHealth* out) const noexcept override {
    out->links = 2;
    for (std::size_t i = 0; i < 2; ++i) fill_link_health(joints_[i].link, &out->link[i]);
  }
  std::vector<std::string> link_names() const override { return {"simulated board 1", "simulated board 2"}; }
  std::vector<int> realtime_peers() const override {
    return {joints_[0].board.process_id(), joints_[1].board.process_id()};
  }
  const SimulationTruthOf<2>* truth() const noexcept override { return this; }

  // The plant's true state.
  Vec2 x_m() const noexcept override { return plant_.handle_m(); }
  Vec2 v_m_per_s() const noexcept override { return plant_.handle_velocity_m_per_s(); }
  Vec2 motor_force_N() const noexcept override;
  Vec2 hand_force_N() const noexcept override { return plant_.hand_force_N(); }

  // Each joint's board, wire and link, for tests (joint_index 0 or 1).
  SimulatedBoard& board(int joint_index) noexcept { return joint(joint_index).board; }
  Wire& wire(int joint_index) noexcept { return joint(joint_index).wire; }
  const BoardLink& link(int joint_index) const noexcept { return joints_[static_cast<std::size_t>(joint_index)].link; }
  BoardLink& mutable_link(int joint_index) noexcept { return joint(joint_index).link; }
  const BoardPair& pair() const noexcept { return pair_; }
  const PlanarPlant& plant() const noexcept { return plant_; }
  // Pulls a board's reset pin.
  void reset_board(int joint_index) noexcept { joint(joint_index).board.reset(); }

 private:
  struct Joint {
    Joint(const std::string& firmware_elf, const BoardLinkConfig& config)
        : board(firmware_elf), wire(board), link(wire, config) {}
    SimulatedBoard board;
    Wire wire;
    BoardLink link;
  };

  Joint& joint(int joint_index) noexcept { return joints_[static_cast<std::size_t>(joint_index)]; }
  std::int64_t now_ns() const noexcept;
  // Runs both boards for one substep of h_s, then moves the plant with their torques.
  void substep(double h_s, bool move_plant) noexcept;

  PlanarModel model_;
  PlanarPlant plant_;
  std::array<Joint, 2> joints_;
  BoardPair pair_;
  Vec2 joint_torque_N_m_{};
  std::uint64_t start_cycle_{};
};

}  // namespace hapscene
