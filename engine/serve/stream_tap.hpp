#pragma once
// The live view's side of the loop: a tick observer that copies each tick (or every
// `stride`-th, see LiveStreamConfig) into a lock-free ring allocated before the run; the
// view's pump thread drains it. A full ring drops the sample and counts it: the loop never
// waits for the view. Script faults are seen here too, as in ScriptFaultPlaces: one flag
// per script of the running scene, looked at after each sampled tick; the first time a
// script is seen disabled its fault message (already stored in the script's own fixed
// buffer, and never changed after) is copied once into a small ring of its own, so the
// pump never touches a script instance (which a reload may be destroying). A device on
// links (serial boards, hil) is asked for its link counters every few ticks, on the
// loop's thread (the device's counters are the loop's), into a third small ring.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "engine/devices/device.hpp"
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

// A script fault, copied once when the tap first sees the script disabled.
inline constexpr std::size_t kStreamFaultBytes = 400;  // the script VM keeps at most this
struct StreamScriptFault {
  std::uint64_t number{};  // 1 for the run's first fault seen, 2 for the next...
  std::uint32_t script{};  // its index among the running scene's scripts (scene order)
  double t_s{};            // run time of the call that faulted
  ScriptFault kind{ScriptFault::none};
  std::size_t length{};
  char message[kStreamFaultBytes]{};  // "scripts/x.lua:12: boom" (printable, not terminated)
};

// Link counters are taken about this many times a second (and at the start and the end).
inline constexpr double kLinkHealthPerSecond = 100.0;

template <int N>
class StreamTapOf final : public TickObserverOf<N> {
 public:
  // `stride`: a sample every stride ticks (1: every tick). `rate_hz`: the scene's.
  StreamTapOf(std::size_t capacity, std::uint64_t stride, double rate_hz = 1000.0)
      : ring_(capacity),
        stride_(stride < 1 ? 1 : stride),
        health_every_(static_cast<std::uint64_t>(
            std::max(1.0, std::floor(rate_hz / kLinkHealthPerSecond / static_cast<double>(stride_))))) {}

  // The device whose links to report (null or a device without links: none). Before the run.
  void set_device(const DeviceStatus* device) noexcept { device_ = device; }

  void on_start(const TickStateOf<N>& /*state*/) override { take_link_health(); }

  void on_scripts(ScriptSpan running, ScriptSpan /*replaced*/) noexcept override {
    // A new version's scripts: their faults are new ones (a fade's end keeps the running span).
    if (running.data() != running_.data() || running.size() != running_.size()) reported_ = 0;
    running_ = running;
  }

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
      if (!running_[i]->disabled()) continue;
      const std::uint64_t bit = std::uint64_t{1} << i;
      s.scripts_disabled |= bit;
      if ((reported_ & bit) == 0) {
        reported_ |= bit;
        publish_fault(i, *running_[i]);
      }
    }
    if (device_ != nullptr && (index / stride_) % health_every_ == 0) take_link_health();
    if constexpr (N > 1) {
      const std::size_t proxies = std::min(state.effect_runs.size(), kStreamProxies);
      for (std::size_t i = 0; i < proxies; ++i) s.proxies_m[i] = state.effect_runs[i].proxy_m;
      s.proxy_count = static_cast<std::uint8_t>(proxies);
    }
    if (!ring_.try_push(s)) dropped_.fetch_add(1, std::memory_order_relaxed);
  }

  void on_finish(const TickStateOf<N>& /*state*/) override {
    take_link_health();
    finished_.store(true, std::memory_order_release);
  }

  // The pump thread.
  bool pop(StreamSampleOf<N>* sample) noexcept { return ring_.try_pop(sample); }
  bool pop_fault(StreamScriptFault* fault) noexcept { return faults_.try_pop(fault); }
  bool pop_link_health(DeviceLinkHealth* health) noexcept { return health_.try_pop(health); }
  // Faults seen (each script of each version once), and those the fault ring had no room for.
  std::uint64_t faults_seen() const noexcept { return faults_seen_.load(std::memory_order_relaxed); }
  std::uint64_t faults_dropped() const noexcept { return faults_dropped_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
  std::uint64_t ticks() const noexcept { return ticks_.load(std::memory_order_relaxed); }
  std::uint64_t stride() const noexcept { return stride_; }
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }

 private:
  // Loop thread: the script's message, copied from its fixed buffer into a fixed slot.
  void publish_fault(std::size_t index, const ScriptInstance& script) noexcept {
    fault_.number = faults_seen_.load(std::memory_order_relaxed) + 1;
    faults_seen_.store(fault_.number, std::memory_order_relaxed);
    fault_.script = static_cast<std::uint32_t>(index);
    fault_.t_s = script.fault_time_s();
    fault_.kind = script.fault();
    const std::string_view message = script.fault_message();
    fault_.length = std::min(message.size(), kStreamFaultBytes);
    std::memcpy(fault_.message, message.data(), fault_.length);
    if (!faults_.try_push(fault_)) faults_dropped_.fetch_add(1, std::memory_order_relaxed);
  }

  // Loop thread (or before the first tick and after the last): the device's link counters.
  void take_link_health() noexcept {
    if (device_ == nullptr) return;
    device_->link_health(&health_slot_);
    if (health_slot_.links > 0) (void)health_.try_push(health_slot_);  // full: the pump has a recent one
  }

  SpscRing<StreamSampleOf<N>> ring_;
  std::uint64_t stride_;
  std::uint64_t health_every_;  // in samples
  ScriptSpan running_;
  std::uint64_t reported_{};  // bit i: script i's fault was published
  StreamScriptFault fault_{};
  SpscRing<StreamScriptFault> faults_{64};
  std::atomic<std::uint64_t> faults_seen_{0};
  std::atomic<std::uint64_t> faults_dropped_{0};
  const DeviceStatus* device_{};
  DeviceLinkHealth health_slot_{};
  SpscRing<DeviceLinkHealth> health_{16};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> ticks_{0};
  std::atomic<bool> finished_{false};
};

}  // namespace hapscene
