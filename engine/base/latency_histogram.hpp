#pragma once
// A fixed-size histogram of durations in nanoseconds for percentiles without allocation
// in the loop: 32 sub-buckets per power of two (relative error under 3 %), exact max.
#include <array>
#include <bit>
#include <cstdint>

namespace hapscene {

class LatencyHistogram {
 public:
  void record(std::uint64_t ns) noexcept {
    ++buckets_[bucket_of(ns)];
    ++count_;
    sum_ns_ += ns;
    if (ns > max_ns_) max_ns_ = ns;
  }

  std::uint64_t count() const noexcept { return count_; }
  std::uint64_t max_ns() const noexcept { return max_ns_; }
  // The sum of the samples (a mean over an interval is the difference of two sums).
  std::uint64_t sum_ns() const noexcept { return sum_ns_; }

  // The smallest recorded value v such that at least `fraction` of samples are <= v
  // (to the bucket's resolution; the bucket's upper edge, never above the max).
  std::uint64_t percentile_ns(double fraction) const noexcept {
    if (count_ == 0) return 0;
    const auto target = static_cast<std::uint64_t>(fraction * static_cast<double>(count_));
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < kBuckets; ++i) {
      seen += buckets_[i];
      if (seen >= target && seen > 0) {
        const std::uint64_t upper = upper_edge(i);
        return upper < max_ns_ ? upper : max_ns_;
      }
    }
    return max_ns_;
  }

  // How many samples were at most `ns` (to the bucket's resolution: buckets whose upper
  // edge is <= ns count whole).
  std::uint64_t count_at_most(std::uint64_t ns) const noexcept {
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < kBuckets && upper_edge(i) <= ns; ++i) seen += buckets_[i];
    return seen;
  }

 private:
  static constexpr std::size_t kSubBits = 5;
  static constexpr std::size_t kSub = std::size_t{1} << kSubBits;
  static constexpr std::size_t kBuckets = 64 * kSub;

  // Values below kSub map to themselves; above, (exponent, top kSubBits mantissa bits).
  static std::size_t bucket_of(std::uint64_t ns) noexcept {
    if (ns < kSub) return static_cast<std::size_t>(ns);
    const auto exponent = static_cast<std::size_t>(std::bit_width(ns)) - 1;  // >= kSubBits
    const std::size_t shift = exponent - kSubBits;
    const std::size_t mantissa = static_cast<std::size_t>(ns >> shift) & (kSub - 1);
    return (shift + 1) * kSub + mantissa;
  }

  static std::uint64_t upper_edge(std::size_t bucket) noexcept {
    if (bucket < kSub) return bucket;
    const std::size_t shift = bucket / kSub - 1;
    const std::uint64_t mantissa = (bucket % kSub) | kSub;
    return ((mantissa + 1) << shift) - 1;
  }

  std::array<std::uint64_t, kBuckets> buckets_{};
  std::uint64_t count_{};
  std::uint64_t sum_ns_{};
  std::uint64_t max_ns_{};
};

}  // namespace hapscene
