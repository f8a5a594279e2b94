#pragma once
// Firmware-in-the-loop (`--device hil`): the real firmware on a simulated ATmega328P
// (simavr), wired to the simulated Hapkit plant, talking to the host engine through the
// same protocol code as a real board on a serial port.
//
// Lock-step in simulated time: advance(dt) runs the AVR for dt worth of cycles in
// substeps; at each substep the plant's handle angle becomes the MR sensor voltage on
// ADC2, the CPU runs, and the PWM duty (OC0B) and direction pin (PB0) it leaves become
// the motor force that moves the plant. The host reads what the board sent over the
// simulated UART, so it sees the board's latency, quantization and faults.
// Deterministic: the same inputs give the same run.
//
// In a real-time run the same world runs on a thread of its own at the wall clock's pace
// (PacedWorld), beside the loop, as a real board does: the host reads what has arrived
// and its time is the wall clock's, and advance() does nothing.
#include <cstdint>
#include <memory>
#include <string>

#include "engine/devices/board_link.hpp"
#include "engine/devices/device.hpp"
#include "engine/devices/hapkit_plant.hpp"
#include "engine/base/published.hpp"
#include "engine/devices/hil/paced_world.hpp"
#include "engine/devices/hil/simulated_board.hpp"
#include "engine/devices/hil/wire.hpp"

namespace hapscene {

struct HilConfig {
  SimulationConfig simulation;
  std::string firmware_elf;
  BoardLinkConfig link{.silence_timeout_ns = 50'000'000,
                       .hello_retry_ns = 5'000'000,
                       .reopen_retry_ns = 500'000'000,
                       .stats_period_ns = 100'000'000};
  double handshake_timeout_s{0.5};  // simulated time
};

class HilHapkit final : public Device, public SimulationTruth {
 public:
  // Loads the firmware (InputError when missing) and runs the handshake in simulated
  // time with the handle held still (std::runtime_error when the board never answers).
  HilHapkit(const DeviceProfile& profile, const HilConfig& config);
  ~HilHapkit() override { end_real_time(); }

  std::int32_t read() noexcept override;
  void write(const MotorCommand& command) noexcept override;
  void advance(double dt_s) noexcept override;
  bool take_restart() noexcept override { return link_.take_restart(); }
  PositionStatus position_status() const noexcept override { return link_.position_status(); }
  bool fault_seen() const noexcept override { return link_.fault_seen() || lost(); }
  bool lost() const noexcept override { return world_.running() ? world_.gone() : board_.lost(); }
  void begin_real_time(double period_s) override;
  void end_real_time() noexcept override;
  std::string report() const override;
  void link_health(DeviceLinkHealth* out) const noexcept override {
    out->links = 1;
    fill_link_health(link_, &out->link[0]);
  }
  std::vector<std::string> link_names() const override { return {"simulated board"}; }
  std::vector<int> realtime_peers() const override { return {board_.process_id(), world_.thread_id()}; }
  const SimulationTruth* truth() const noexcept override { return this; }

  // The plant's true state after the latest substep (observers: `run --plot`, the
  // recorder), from any thread.
  double x_m() const noexcept override { return truth_.load().x_m; }
  double v_m_per_s() const noexcept override { return truth_.load().v_m_per_s; }
  double motor_force_N() const noexcept override { return truth_.load().motor_force_N; }
  double hand_force_N() const noexcept override { return truth_.load().hand_force_N; }
  double hand_target_m() const noexcept override { return truth_.load().hand_target_m; }

  // The board pins and the link, for tests (in lock-step).
  double t_s() const noexcept { return plant_.t_s(); }
  double motor_duty() const noexcept { return board_.motor_duty(); }
  std::uint64_t cycle() const noexcept { return board_.cycle(); }
  const BoardLink& link() const noexcept { return link_; }
  BoardLink& mutable_link() noexcept { return link_; }
  Wire& wire() noexcept { return wire_; }
  const SimulatedBoard& board() const noexcept { return board_; }
  // The world's pace in real time (after the run).
  const PacedWorld& world() const noexcept { return world_; }
  // Pulls the board's reset pin.
  void reset_board() noexcept { board_.reset(); }

 private:
  struct Truth {
    double x_m, v_m_per_s, motor_force_N, hand_force_N, hand_target_m;
  };

  // The host's time: the board's (simulated) in lock-step, the wall clock's while paced;
  // never backwards across the switch.
  std::int64_t now_ns() const noexcept;
  std::int64_t board_ns() const noexcept { return SimulatedBoard::cycles_to_ns(board_.cycle()); }
  // Runs the board for one substep of h_s, then moves the plant with its motor force;
  // in lock-step the host's link then receives what the board sent (`host_receives`).
  void substep(double h_s, bool move_plant, bool host_receives) noexcept;
  static bool paced_substep(void* self, double h_s) noexcept;

  HapkitPlant plant_;
  SimulatedBoard board_;
  Wire wire_;
  BoardLink link_;
  double motor_force_N_{};
  std::uint64_t start_cycle_{};
  Published<Truth> truth_;
  PacedWorld world_{&HilHapkit::paced_substep, this};
  int substeps_per_tick_{10};
  std::int64_t paced_from_ns_{};  // the host's time when the world started its pace
  std::int64_t after_paced_ns_{};  // how far the host's time ran ahead of the board's while paced
};

}  // namespace hapscene
