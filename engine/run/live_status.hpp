#pragma once
// The latest tick's values, published by the loop with relaxed atomic stores and read by
// another thread (the terminal status line): no lock, no wait on the loop's side.
//
// Script log messages are drained from that other thread too. The loop never hands it a
// container it changes: it publishes which instance arrays are alive (on_scripts, a
// seqlock of two pointer/length pairs written only by the loop), and a drain reads a
// consistent copy of that under a mutex that only threads off the loop take. The reload
// thread drains a replaced scene under the same mutex before destroying it
// (drain_retired), and the loop hands a scene back only after leaving it out of the
// published list, so a drain never reads an instance being destroyed. What is left when
// the run ends is drained on the loop's thread after the last tick (on_finish).
#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/run/hot_swap.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

template <int N>
class LiveStatusOf final : public TickObserverOf<N> {
 public:
  void on_scripts(ScriptSpan running, ScriptSpan replaced) noexcept override {
    // A sequence lock without fences (which ThreadSanitizer does not model): each word's
    // release store orders the odd sequence before it, and the reader's acquire loads of the
    // words order its second read of the sequence after them (engine/base/published.hpp).
    const std::uint64_t sequence = sequence_.load(std::memory_order_relaxed);
    sequence_.store(sequence + 1, std::memory_order_relaxed);
    const ScriptSpan spans[2] = {running, replaced};
    for (std::size_t i = 0; i < 2; ++i) {
      data_[i].store(spans[i].data(), std::memory_order_release);
      size_[i].store(spans[i].size(), std::memory_order_release);
    }
    sequence_.store(sequence + 2, std::memory_order_release);
  }

  void on_finish(const TickStateOf<N>& state) override {
    (void)state;
    std::lock_guard lock(log_mutex_);
    drain_published();
    on_scripts({}, {});  // nothing is drained from here on
  }

  // Moves the script log messages so far into `out` (not from the loop's thread).
  void drain_log(std::vector<std::string>* out) {
    std::lock_guard lock(log_mutex_);
    drain_published();
    out->insert(out->end(), log_.begin(), log_.end());
    log_.clear();
  }

  // The reload thread, before destroying a scene the loop let go of: keeps its messages.
  void drain_retired(LoadedSceneOf<N>& retired) {
    std::lock_guard lock(log_mutex_);
    for (const auto& script : retired.scripts) script->drain_log(&log_);
  }

  void on_tick(const TickStateOf<N>& state) noexcept override {
    for (int i = 0; i < N; ++i) {
      x_m_[i].store(component(state.x_m, i), std::memory_order_relaxed);
      output_N_[i].store(component(state.output_N, i), std::memory_order_relaxed);
    }
    ticks_.store(state.tick, std::memory_order_relaxed);
  }

  // Each axis is read on its own: the components may be a tick apart (a display only).
  Axes<N> x_m() const noexcept { return load(x_m_); }
  Axes<N> output_N() const noexcept { return load(output_N_); }
  std::uint64_t ticks() const noexcept { return ticks_.load(std::memory_order_relaxed); }

 private:
  // With log_mutex_ held: a consistent copy of the published arrays, then their messages.
  void drain_published() {
    const std::unique_ptr<ScriptInstance>* data[2];
    std::size_t size[2];
    for (;;) {
      const std::uint64_t before = sequence_.load(std::memory_order_acquire);
      if ((before & 1) == 0) {
        for (std::size_t i = 0; i < 2; ++i) {
          data[i] = data_[i].load(std::memory_order_acquire);
          size[i] = size_[i].load(std::memory_order_acquire);
        }
        if (sequence_.load(std::memory_order_relaxed) == before) break;
      }
      std::this_thread::yield();
    }
    for (std::size_t i = 0; i < 2; ++i) {
      for (std::size_t k = 0; k < size[i]; ++k) data[i][k]->drain_log(&log_);
    }
  }

  static Axes<N> load(const std::array<std::atomic<double>, N>& values) noexcept {
    if constexpr (N == 1) {
      return values[0].load(std::memory_order_relaxed);
    } else {
      Axes<N> out{};
      for (int i = 0; i < N; ++i) out[i] = values[i].load(std::memory_order_relaxed);
      return out;
    }
  }

  std::array<std::atomic<double>, N> x_m_{};
  std::array<std::atomic<double>, N> output_N_{};
  std::atomic<std::uint64_t> ticks_{0};
  // The published instance arrays (running, replaced).
  std::atomic<std::uint64_t> sequence_{0};
  std::atomic<const std::unique_ptr<ScriptInstance>*> data_[2]{};
  std::atomic<std::size_t> size_[2]{};
  std::mutex log_mutex_;
  std::vector<std::string> log_;
};

using LiveStatus = LiveStatusOf<1>;

}  // namespace hapscene
