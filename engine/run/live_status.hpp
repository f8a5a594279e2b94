#pragma once
// The latest tick's values, published by the loop with relaxed atomic stores and read by
// another thread (the terminal status line): no lock, no wait on the loop's side. Script
// log messages are drained from the same other thread; what is left when the run ends is
// drained on the loop's thread after the last tick (the mutex only orders those two).
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "engine/run/runner.hpp"

namespace hapscene {

class LiveStatus final : public TickObserver {
 public:
  void on_start(const TickState& state) override {
    std::lock_guard lock(log_mutex_);
    scripts_ = &state.scripts;
  }

  void on_finish(const TickState& state) override {
    std::lock_guard lock(log_mutex_);
    for (const auto& script : state.scripts) script->drain_log(&log_);
    scripts_ = nullptr;
  }

  // Moves the script log messages so far into `out` (not from the loop's thread).
  void drain_log(std::vector<std::string>* out) {
    std::lock_guard lock(log_mutex_);
    if (scripts_ != nullptr) {
      for (const auto& script : *scripts_) script->drain_log(&log_);
    }
    out->insert(out->end(), log_.begin(), log_.end());
    log_.clear();
  }

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
  std::mutex log_mutex_;
  const std::vector<std::unique_ptr<ScriptInstance>>* scripts_{nullptr};
  std::vector<std::string> log_;
};

}  // namespace hapscene
