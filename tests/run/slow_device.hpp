#pragma once
// A simulated Hapkit whose read() takes time on chosen ticks (a device that blocks the
// loop), on a SteppedClock: the real-time loop's own work overruns its deadline there,
// exactly as long as asked, on any machine (the overrun tests of tests/run). (Not
// advance(): the time a device's simulation takes there is the simulated world's, not the
// loop's; see RunOptions::overrun_fault_ticks.) A device with a motor, as far as the loop
// knows (deadlines_matter): overruns stop its runs.
#include <chrono>
#include <cstdint>
#include <functional>
#include <utility>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/scene/scene.hpp"
#include "tests/run/stepped_clock.hpp"

namespace hapscene::test {

class SlowDevice final : public Device {
 public:
  SlowDevice(const Scene& scene, SteppedClock& clock, std::function<bool(std::uint64_t)> slow_tick,
             std::chrono::microseconds slow_for = std::chrono::microseconds(1600))
      : inner_(scene.device, SimulationConfig{}), clock_(clock), slow_tick_(std::move(slow_tick)), slow_for_(slow_for) {}
  std::int32_t read() noexcept override {
    if (slow_tick_(ticks_)) clock_.pass(std::chrono::nanoseconds(slow_for_).count());
    return inner_.read();
  }
  void write(const MotorCommand& command) noexcept override {
    last = command;
    inner_.write(command);
  }
  void advance(double dt_s) noexcept override {
    ++ticks_;
    inner_.advance(dt_s);
  }
  MotorCommand last{};

 private:
  SimulatedHapkit inner_;
  SteppedClock& clock_;
  std::function<bool(std::uint64_t)> slow_tick_;
  std::chrono::microseconds slow_for_;
  std::uint64_t ticks_{};
};

}  // namespace hapscene::test
