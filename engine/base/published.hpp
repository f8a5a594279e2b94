#pragma once
// One value that one thread writes and others read, without a lock and without waiting on
// each other: the writer never waits, and a reader never waits for a write under way (a
// writer preempted halfway, by the loop's own SCHED_FIFO thread say, cannot stall a reader).
//
// Two slots, each a sequence lock over atomic words (every access atomic, so
// ThreadSanitizer sees every ordering) that also holds its store's number. Store k writes
// slot k % 2, then publishes k; a reader reads the slot of the latest published store k it
// saw and takes it only when the slot still holds store k: a slot the writer has meanwhile
// rewritten with k + 2 (not yet published, and newer than what a later read may see
// published) is read again from the newest number, so reads never go back in time.
//   slot write: sequence odd (relaxed), each word with release, sequence even with release
//   slot read:  sequence (acquire), each word (acquire), sequence again; equal and even: done
// A reader that saw a word of a write under way synchronizes with that word's release, so
// its second read of the sequence sees the write's odd (or a later) number.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace hapscene {

template <class T>
class Published {
  static_assert(std::is_trivially_copyable_v<T>, "a published value is copied word by word");
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;

 public:
  explicit Published(const T& initial = T{}) noexcept { store(initial); }

  // From the one writing thread.
  void store(const T& value) noexcept {
    std::uint64_t words[kWords]{};
    std::memcpy(words, &value, sizeof(T));
    const std::uint64_t number = latest_.load(std::memory_order_relaxed) + 1;
    Slot& slot = slots_[number & 1];
    const std::uint64_t sequence = slot.sequence.load(std::memory_order_relaxed);
    slot.sequence.store(sequence + 1, std::memory_order_relaxed);
    slot.number.store(number, std::memory_order_release);
    for (std::size_t i = 0; i < kWords; ++i) slot.words[i].store(words[i], std::memory_order_release);
    slot.sequence.store(sequence + 2, std::memory_order_release);
    latest_.store(number, std::memory_order_release);
  }

  // From any thread.
  T load() const noexcept {
    std::uint64_t words[kWords];
    for (;;) {
      const std::uint64_t number = latest_.load(std::memory_order_acquire);
      const Slot& slot = slots_[number & 1];
      const std::uint64_t before = slot.sequence.load(std::memory_order_acquire);
      if ((before & 1) != 0) continue;  // being rewritten: the other slot holds a newer store
      const std::uint64_t held = slot.number.load(std::memory_order_acquire);
      for (std::size_t i = 0; i < kWords; ++i) words[i] = slot.words[i].load(std::memory_order_acquire);
      if (slot.sequence.load(std::memory_order_relaxed) == before && held == number) break;
    }
    T value;
    std::memcpy(&value, words, sizeof(T));
    return value;
  }

 private:
  struct Slot {
    std::atomic<std::uint64_t> sequence{0};
    std::atomic<std::uint64_t> number{0};  // the store it holds
    std::atomic<std::uint64_t> words[kWords]{};
  };
  std::atomic<std::uint64_t> latest_{0};
  Slot slots_[2];
};

}  // namespace hapscene
