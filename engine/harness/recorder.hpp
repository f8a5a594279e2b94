#pragma once
// Records every tick of a simulated run, with the simulator's true state beside what
// the host saw. Memory is reserved before the run; a run longer than the reservation
// stops recording (and says so) rather than allocate in the loop. Without a simulated
// device (a real one), the "true" fields repeat what the host measured.
#include <cmath>
#include <cstddef>
#include <vector>

#include "engine/devices/device.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

struct TickRecord {
  double t_s{};
  double x_true_m{};          // the simulator's handle position at the tick
  double v_true_m_per_s{};    // and velocity
  double x_m{};               // what the host measured
  double v_m_per_s{};         // what the host estimated (0 when the scene needs none)
  double requested_N{};       // sum of the effects
  double output_N{};          // after safety
  double motor_N{};           // what the motor applies (PWM quantized, saturated)
  double hand_N{};            // the hand's force on the handle
  double hand_target_m{NAN};  // where the hand pulls the handle (NaN: no hand gripping)
};

// One tick as the host saw it, beside the simulator's truth (`truth` null: a real device,
// whose "true" fields repeat what the host measured and whose motor is taken to apply
// the commanded force).
inline TickRecord tick_record(const TickState& s, const SimulationTruth* truth) noexcept {
  if (truth == nullptr) {
    return {s.t_s, s.x_m, s.v_m_per_s, s.x_m, s.v_m_per_s, s.effects_force_N, s.output_N, s.output_N, 0.0};
  }
  return {s.t_s,           truth->x_m(),      truth->v_m_per_s(),        s.x_m,
          s.v_m_per_s,     s.effects_force_N, s.output_N,                truth->motor_force_N(),
          truth->hand_force_N(),   truth->hand_target_m()};
}

class Recorder final : public TickObserver {
 public:
  Recorder(const SimulationTruth* truth, std::size_t capacity) : truth_(truth) {
    records_.reserve(capacity);
  }

  void on_tick(const TickState& s) noexcept override {
    if (records_.size() == records_.capacity()) {
      ++dropped_;
      return;
    }
    records_.push_back(tick_record(s, truth_));
  }

  const std::vector<TickRecord>& records() const { return records_; }
  std::vector<TickRecord> take() { return std::move(records_); }
  std::size_t dropped() const { return dropped_; }

 private:
  const SimulationTruth* truth_;
  std::vector<TickRecord> records_;
  std::size_t dropped_{};
};

}  // namespace hapscene
