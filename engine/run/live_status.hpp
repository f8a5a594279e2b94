#pragma once
// The latest tick's values, published by the loop with relaxed atomic stores and read by
// another thread (the terminal status line): no lock, no wait on the loop's side.
#include <atomic>
#include <cstdint>

#include "engine/run/runner.hpp"

namespace hapscene {

class LiveStatus final : public TickObserver {
 public:
  void on_tick(const TickState& state) noexcept override {
    x_m_.store(state.x_m, std::memory_order_relaxed);
    output_N_.store(state.output_N, std::memory_order_relaxed);
    ticks_.store(state.tick, std::memory_order_relaxed);
  }

  double x_m() const noexcept { return x_m_.load(std::memory_order_relaxed); }
  double output_N() const noexcept { return output_N_.load(std::memory_order_relaxed); }
  std::uint64_t ticks() const noexcept { return ticks_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> x_m_{0.0};
  std::atomic<double> output_N_{0.0};
  std::atomic<std::uint64_t> ticks_{0};
};

}  // namespace hapscene
