#pragma once
// Timing ticks with the time-stamp counter, converted to ns with a frequency calibrated
// against the steady clock. The median comes from batches of 64 ticks timed as a whole (a
// counter read costs about as much as a short tick, and is coarse on some virtual
// machines); the tail (p99, p99.9, max) from each tick timed alone, minus the cost of the
// counter reads measured around an empty call.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace hapscene {

struct TickCost {
  std::uint64_t ticks{};
  double median_ns{};
  double p99_ns{};
  double p999_ns{};
  double max_ns{};
  double ratio{-1.0};                  // median against the reference of its comparison (< 0: none)
  double instructions_per_tick{-1.0};  // < 0: not counted (no performance counters)
};

class TickTimer {
 public:
  TickTimer();

  static constexpr std::size_t kBatch = 64;

  // Times `tick(i)` for i in [0, count) in batches: the median batch's ns per tick.
  template <typename Tick>
  double batch_median_ns(std::size_t count, Tick&& tick) {
    batch_ns_.clear();
    for (std::size_t first = 0; first + kBatch <= count; first += kBatch) {
      const std::uint64_t begin = now_ticks();
      for (std::size_t i = first; i < first + kBatch; ++i) tick(i);
      const std::uint64_t end = now_ticks();
      batch_ns_.push_back(static_cast<double>(end - begin) * ns_per_tick_ / kBatch);
    }
    if (batch_ns_.empty()) return 0.0;
    const auto middle = batch_ns_.begin() + static_cast<std::ptrdiff_t>(batch_ns_.size() / 2);
    std::nth_element(batch_ns_.begin(), middle, batch_ns_.end());
    return *middle;
  }

  // Times `tick(i)` for i in [0, count) one tick at a time, in kTailRepeats equal parts:
  // fills the tail fields of a cost (ticks; p99 and p99.9 as the median of the parts' own,
  // so a burst of outside noise in one part does not decide them; max of all). `tick`
  // must accept being called again with the same i.
  static constexpr std::size_t kTailRepeats = 5;
  template <typename Tick>
  void time_tail(std::size_t count, Tick&& tick, TickCost* cost) {
    const std::size_t part = count / kTailRepeats;
    std::vector<double> p99(kTailRepeats), p999(kTailRepeats);
    cost->ticks = 0;
    cost->max_ns = 0.0;
    for (std::size_t r = 0; r < kTailRepeats; ++r) {
      time_each(part, [&](std::size_t i) { tick(r * part + i); });
      const Tail tail = summarise_tail();
      p99[r] = tail.p99_ns;
      p999[r] = tail.p999_ns;
      cost->max_ns = std::max(cost->max_ns, tail.max_ns);
      cost->ticks += part;
    }
    std::sort(p99.begin(), p99.end());
    std::sort(p999.begin(), p999.end());
    cost->p99_ns = p99[kTailRepeats / 2];
    cost->p999_ns = p999[kTailRepeats / 2];
  }

 private:
  static std::uint64_t now_ticks() noexcept {
#if defined(__x86_64__) || defined(__i386__)
    _mm_lfence();
    const std::uint64_t t = __rdtsc();
    _mm_lfence();
    return t;
#else
    return static_cast<std::uint64_t>(
        std::chrono::steady_clock::now().time_since_epoch().count());
#endif
  }

  template <typename Tick>
  void time_each(std::size_t count, Tick&& tick) {
    samples_.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint64_t begin = now_ticks();
      tick(i);
      const std::uint64_t end = now_ticks();
      samples_[i] = end - begin;
    }
  }

  struct Tail {
    double p99_ns{}, p999_ns{}, max_ns{};
  };
  Tail summarise_tail();

  std::vector<double> batch_ns_;
  std::vector<std::uint64_t> samples_;
  double ns_per_tick_{1.0};
  double overhead_ticks_{0.0};
};

}  // namespace hapscene
