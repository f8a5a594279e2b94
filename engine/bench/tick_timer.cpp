#include "engine/bench/tick_timer.hpp"

#include <thread>

namespace hapscene {

TickTimer::TickTimer() {
  // Frequency: time-stamp counter against the steady clock over 50 ms.
  using Clock = std::chrono::steady_clock;
  const auto wall_begin = Clock::now();
  const std::uint64_t begin = now_ticks();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::uint64_t end = now_ticks();
  const double wall_ns = std::chrono::duration<double, std::nano>(Clock::now() - wall_begin).count();
  ns_per_tick_ = wall_ns / static_cast<double>(end - begin);

  // Overhead: the median of timing an empty call.
  time_each(100000, [](std::size_t) {});
  std::nth_element(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(samples_.size() / 2),
                   samples_.end());
  overhead_ticks_ = static_cast<double>(samples_[samples_.size() / 2]);
}

TickTimer::Tail TickTimer::summarise_tail() {
  Tail tail;
  if (samples_.empty()) return tail;
  std::sort(samples_.begin(), samples_.end());
  const auto at = [&](double fraction) {
    const auto index = static_cast<std::size_t>(fraction * static_cast<double>(samples_.size() - 1));
    const double ticks = static_cast<double>(samples_[index]) - overhead_ticks_;
    return std::max(0.0, ticks) * ns_per_tick_;
  };
  tail.p99_ns = at(0.99);
  tail.p999_ns = at(0.999);
  tail.max_ns = at(1.0);
  return tail;
}

}  // namespace hapscene
