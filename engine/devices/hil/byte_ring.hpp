#pragma once
// A byte queue between exactly two threads, one pushing and one taking, without locks:
// the serial line between the host's link and a simulated board that runs on a thread of
// its own (PacedWorld). Nothing allocates; a full ring refuses the byte.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace hapscene {

template <std::size_t Capacity>
class ByteRing {
  static_assert(Capacity > 0 && (Capacity & (Capacity - 1)) == 0, "a power of two");

 public:
  // The pushing thread: false (nothing queued) when the ring is full.
  bool push(std::uint8_t byte) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail - head_.load(std::memory_order_acquire) == Capacity) return false;
    bytes_[tail & (Capacity - 1)] = byte;
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // The taking thread: the oldest byte without taking it; false when the ring is empty.
  bool peek(std::uint8_t* byte) const noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == tail_.load(std::memory_order_acquire)) return false;
    *byte = bytes_[head & (Capacity - 1)];
    return true;
  }
  // The taking thread, after a peek that returned true: that byte is taken.
  void drop_peeked() noexcept { head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

  bool pop(std::uint8_t* byte) noexcept {
    if (!peek(byte)) return false;
    drop_peeked();
    return true;
  }

 private:
  std::array<std::uint8_t, Capacity> bytes_{};
  std::atomic<std::size_t> head_{0};  // next byte to take
  std::atomic<std::size_t> tail_{0};  // next free place
};

}  // namespace hapscene
