#pragma once
// The live view's side of the loop: a tick observer that copies each tick (or every
// `stride`-th, see LiveStreamConfig) into a lock-free ring allocated before the run; the
// view's pump thread drains it. A full ring drops the sample and counts it: the loop never
// waits for the view. Script faults are seen here too, as in ScriptFaultPlaces: one flag
// per script of the running scene, looked at after each tick.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "engine/effects/script_effect.hpp"
#include "engine/run/telemetry_ring.hpp"
#include "engine/run/tick_observer.hpp"

namespace hapscene {

// Shapes whose proxies a sample carries (a 2-D scene's first ones, in the bank's order).
inline constexpr std::size_t kStreamProxies = 8;

template <int N>
struct StreamSampleOf {
  std::uint64_t tick{};  // the tick's index from the run's start (0: the first)
  double t_s{};
  Axes<N> x_m{};
  Axes<N> v_m_per_s{};
  Axes<N> force_N{};
  Axes<N> output_N{};
  SafetyCounters safety{};
  std::uint64_t scripts_disabled{};  // bit i: script i of the running scene is disabled
  std::array<Vec2, (N > 1 ? kStreamProxies : 0)> proxies_m{};
  std::uint8_t proxy_count{};
};

template <int N>
class StreamTapOf final : public TickObserverOf<N> {
 public:
  // `stride`: a sample every stride ticks (1: every tick).
  StreamTapOf(std::size_t capacity, std::uint64_t stride) : ring_(capacity), stride_(stride < 1 ? 1 : stride) {}

  void on_scripts(ScriptSpan running, ScriptSpan /*replaced*/) noexcept override { running_ = running; }

  void on_tick(const TickStateOf<N>& state) noexcept override {
    ticks_.store(state.tick, std::memory_order_relaxed);
    // The tick's index from 0 (state.tick counts the ticks done, this one included).
    const std::uint64_t index = state.tick - 1;
    if (index % stride_ != 0) return;
    StreamSampleOf<N> s;
    s.tick = index;
    s.t_s = state.t_s;
    s.x_m = state.x_m;
    s.v_m_per_s = state.v_m_per_s;
    s.force_N = state.effects_force_N;
    s.output_N = state.output_N;
    s.safety = state.safety.counters;
    const std::size_t scripts = std::min<std::size_t>(running_.size(), 64);
    for (std::size_t i = 0; i < scripts; ++i) {
      if (running_[i]->disabled()) s.scripts_disabled |= std::uint64_t{1} << i;
    }
    if constexpr (N > 1) {
      const std::size_t proxies = std::min(state.effect_runs.size(), kStreamProxies);
      for (std::size_t i = 0; i < proxies; ++i) s.proxies_m[i] = state.effect_runs[i].proxy_m;
      s.proxy_count = static_cast<std::uint8_t>(proxies);
    }
    if (!ring_.try_push(s)) dropped_.fetch_add(1, std::memory_order_relaxed);
  }

  void on_finish(const TickStateOf<N>& /*state*/) override { finished_.store(true, std::memory_order_release); }

  // The pump thread.
  bool pop(StreamSampleOf<N>* sample) noexcept { return ring_.try_pop(sample); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
  std::uint64_t ticks() const noexcept { return ticks_.load(std::memory_order_relaxed); }
  std::uint64_t stride() const noexcept { return stride_; }
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }

 private:
  SpscRing<StreamSampleOf<N>> ring_;
  std::uint64_t stride_;
  ScriptSpan running_;
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> ticks_{0};
  std::atomic<bool> finished_{false};
};

}  // namespace hapscene
