#pragma once
// A TickLoop (engine/bench/tick_bench.hpp) around a callable that takes one reading (an
// int32: a sensor count for 1-DOF loops, an index into recorded readings for 2-DOF ones).
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/bench/tick_bench.hpp"

namespace hapscene {

// A TickLoop around a callable taking one reading: the callable is inlined into each
// timing loop, so the only per-tick overhead is the call the implementation itself makes.
template <typename Tick>
class TickLoopOf : public TickLoop {
 public:
  explicit TickLoopOf(Tick tick) : tick_(std::move(tick)) {}

  double time_slice(TickTimer& timer, const std::vector<std::int32_t>& counts, std::size_t begin,
                    std::size_t end) override {
    const std::int32_t* first = counts.data() + begin;
    return timer.batch_median_ns(end - begin, [&](std::size_t i) { tick_(first[i]); });
  }
  void time_tail(TickTimer& timer, const std::vector<std::int32_t>& counts, int passes,
                 TickCost* cost) override {
    const std::size_t n = counts.size();
    timer.time_tail(n * static_cast<std::size_t>(passes), [&](std::size_t i) { tick_(counts[i % n]); }, cost);
  }
  double instructions_per_tick(InstructionCounter& counter, const std::vector<std::int32_t>& counts) override {
    if (counts.empty()) return -1.0;
    counter.start();
    for (const std::int32_t raw : counts) tick_(raw);
    return static_cast<double>(counter.stop()) / static_cast<double>(counts.size());
  }

 protected:
  Tick tick_;
};

}  // namespace hapscene
