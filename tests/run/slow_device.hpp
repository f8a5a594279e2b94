#pragma once
// A simulated Hapkit whose read() burns real time on chosen ticks (a device that blocks
// the loop), so that the real-time loop's own work overruns its deadline there (the
// overrun tests of tests/run). (Not advance(): the time a device's simulation takes there
// is the simulated world's, not the loop's; see RunOptions::overrun_fault_ticks.)
#include <chrono>
#include <cstdint>
#include <functional>
#include <utility>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene::test {

class SlowDevice final : public Device {
 public:
  SlowDevice(const Scene& scene, std::function<bool(std::uint64_t)> slow_tick,
             std::chrono::microseconds slow_for = std::chrono::microseconds(1600))
      : inner_(scene.device, SimulationConfig{}), slow_tick_(std::move(slow_tick)), slow_for_(slow_for) {}
  std::int32_t read() noexcept override {
    if (slow_tick_(ticks_)) {
      const auto until = std::chrono::steady_clock::now() + slow_for_;
      while (std::chrono::steady_clock::now() < until) {
      }
    }
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
  std::function<bool(std::uint64_t)> slow_tick_;
  std::chrono::microseconds slow_for_;
  std::uint64_t ticks_{};
};

}  // namespace hapscene::test
