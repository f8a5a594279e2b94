#include "engine/lua/log_queue.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "engine/base/format.hpp"

namespace hapscene::detail {

void LogQueue::configure(double messages_per_s, std::size_t burst) {
  rate_per_s_ = std::max(0.0, messages_per_s);
  burst_ = static_cast<double>(std::min(burst, kSlots));
  tokens_ = burst_;
  last_t_s_ = 0.0;
}

// Token bucket: refills with run time, so the limit is the same at any simulation speed.
bool LogQueue::admit(double t_s) noexcept {
  if (t_s > last_t_s_) {
    tokens_ = std::min(burst_, tokens_ + (t_s - last_t_s_) * rate_per_s_);
  }
  last_t_s_ = t_s;  // a restart moves time back: refill from there
  if (tokens_ >= 1.0) {
    tokens_ -= 1.0;
    return true;
  }
  dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

// The producer owns slots [head, tail + kSlots); it may write one when the ring is not full.
char* LogQueue::begin_write() noexcept {
  const std::uint64_t head = head_.load(std::memory_order_relaxed);
  const std::uint64_t tail = tail_.load(std::memory_order_acquire);
  if (head - tail >= kSlots) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return nullptr;
  }
  return slots_[head % kSlots].text;
}

void LogQueue::commit(double t_s, std::size_t length) noexcept {
  const std::uint64_t head = head_.load(std::memory_order_relaxed);
  Slot& slot = slots_[head % kSlots];
  slot.t_s = t_s;
  slot.length = std::min(length, kTextBytes);
  head_.store(head + 1, std::memory_order_release);
}

// Copies out every published slot, then frees them for the producer.
void LogQueue::drain(std::string_view script_name, std::vector<std::string>* out) {
  const std::uint64_t head = head_.load(std::memory_order_acquire);
  std::uint64_t tail = tail_.load(std::memory_order_relaxed);
  for (; tail != head; ++tail) {
    const Slot& slot = slots_[tail % kSlots];
    char time[48];
    std::snprintf(time, sizeof time, " (t = %.3f s)", slot.t_s);
    // What the script logged is printed as it is, but printable (engine/base/format.hpp).
    out->push_back(printable(std::string_view(slot.text, slot.length)) + time);
    tail_.store(tail + 1, std::memory_order_release);
  }
  const std::uint64_t dropped = dropped_.exchange(0, std::memory_order_relaxed);
  if (dropped > 0) {
    char line[160];
    std::snprintf(line, sizeof line,
                  ": %llu log message%s dropped (at most %g per second, bursts of %g)",
                  static_cast<unsigned long long>(dropped), dropped == 1 ? "" : "s",
                  rate_per_s_, burst_);
    out->push_back(printable(script_name) + line);
  }
}

}  // namespace hapscene::detail
