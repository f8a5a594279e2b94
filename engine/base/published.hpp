#pragma once
// One value that one thread writes and others read, without a lock: a sequence lock over
// atomic words, so every access is atomic and ThreadSanitizer sees every ordering. The
// writer never waits; a reader retries while a write is under way and always gets a value
// one write left whole.
//   writer: sequence odd (relaxed), each word with release, sequence even with release
//   reader: sequence (acquire), each word (acquire), sequence again; equal and even: done
// A reader that saw a word of a write under way synchronizes with that word's release,
// so its second read of the sequence sees the write's odd (or a later) number.
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
    const std::uint64_t sequence = sequence_.load(std::memory_order_relaxed);
    sequence_.store(sequence + 1, std::memory_order_relaxed);
    for (std::size_t i = 0; i < kWords; ++i) words_[i].store(words[i], std::memory_order_release);
    sequence_.store(sequence + 2, std::memory_order_release);
  }

  // From any thread.
  T load() const noexcept {
    std::uint64_t words[kWords];
    for (;;) {
      const std::uint64_t before = sequence_.load(std::memory_order_acquire);
      if ((before & 1) != 0) continue;
      for (std::size_t i = 0; i < kWords; ++i) words[i] = words_[i].load(std::memory_order_acquire);
      if (sequence_.load(std::memory_order_relaxed) == before) break;
    }
    T value;
    std::memcpy(&value, words, sizeof(T));
    return value;
  }

 private:
  std::atomic<std::uint64_t> sequence_{0};
  std::atomic<std::uint64_t> words_[kWords]{};
};

}  // namespace hapscene
