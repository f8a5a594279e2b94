#pragma once
// A lock-free single-producer single-consumer ring of fixed capacity, allocated once
// before the run. The haptic loop pushes (never blocks: a full ring refuses the sample
// and the caller counts it as dropped); another thread pops.
#include <atomic>
#include <cstddef>
#include <memory>
#include <new>

namespace hapscene {

template <typename T>
class SpscRing {
 public:
  // Rounds the capacity up to a power of two (at least 2).
  explicit SpscRing(std::size_t capacity) {
    std::size_t size = 2;
    while (size < capacity) size *= 2;
    mask_ = size - 1;
    slots_ = std::make_unique<T[]>(size);
  }

  std::size_t capacity() const noexcept { return mask_ + 1; }

  // Producer only. False when full (nothing written).
  bool try_push(const T& value) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_cache_ > mask_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (head - tail_cache_ > mask_) return false;
    }
    slots_[head & mask_] = value;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer only. False when empty.
  bool try_pop(T* value) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_cache_) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (tail == head_cache_) return false;
    }
    *value = slots_[tail & mask_];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

 private:
  static constexpr std::size_t kLine = 64;  // keep producer and consumer indices apart
  std::unique_ptr<T[]> slots_;
  std::size_t mask_{};
  alignas(kLine) std::atomic<std::size_t> head_{0};  // next slot to write (producer)
  std::size_t tail_cache_{0};                         // producer's view of tail
  alignas(kLine) std::atomic<std::size_t> tail_{0};  // next slot to read (consumer)
  std::size_t head_cache_{0};                         // consumer's view of head
};

}  // namespace hapscene
