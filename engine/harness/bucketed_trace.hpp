#pragma once
// A run's trace for its figure in a fixed amount of memory, whatever the run's length,
// over any record type. Runs up to `max_records` ticks are kept tick by tick; longer runs
// are cut into equal buckets of whole ticks and each bucket keeps two of its ticks, in
// time order (one when they are the same tick): the one where Keep::low(record) is lowest
// and the one where Keep::high(record) is highest (the earliest of equals). A 1-DOF run
// keeps its lowest and highest force (RunTrace); a 2-DOF run its first tick (low: the
// time) and its largest force magnitude (PlanarTrace). Every record is a real tick, so no
// force peak disappears. Memory is reserved at construction; add() never allocates.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hapscene {

template <class Record, class Keep>
class BucketedTrace {
 public:
  // `planned_ticks`: the run's length (duration x rate); a run that goes longer stops
  // recording and counts the ticks it dropped.
  BucketedTrace(std::uint64_t planned_ticks, std::size_t max_records) {
    const std::uint64_t buckets = max_records / 2;
    ticks_per_bucket_ = planned_ticks + 1 <= max_records ? 1 : (planned_ticks + buckets - 1) / buckets;
    records_.reserve(max_records);
  }

  void add(const Record& r) noexcept {
    if (ticks_per_bucket_ == 1) {
      push(r);
      return;
    }
    if (in_bucket_ == 0 || Keep::low(r) < low_key_) {
      low_ = r;
      low_key_ = Keep::low(r);
    }
    if (in_bucket_ == 0 || Keep::high(r) > high_key_) {
      high_ = r;
      high_key_ = Keep::high(r);
    }
    if (++in_bucket_ == ticks_per_bucket_) finish();
  }

  // Closes the bucket in progress (the run ended within it).
  void finish() noexcept {
    if (in_bucket_ == 0) return;
    const Record& first = low_.t_s <= high_.t_s ? low_ : high_;
    const Record& second = low_.t_s <= high_.t_s ? high_ : low_;
    push(first);
    if (second.t_s != first.t_s) push(second);
    in_bucket_ = 0;
  }

  const std::vector<Record>& records() const { return records_; }
  std::uint64_t ticks_per_bucket() const { return ticks_per_bucket_; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  void push(const Record& r) noexcept {
    if (records_.size() == records_.capacity()) {
      ++dropped_;
      return;
    }
    records_.push_back(r);
  }

  std::uint64_t ticks_per_bucket_{1};
  std::uint64_t in_bucket_{0};
  Record low_{};
  Record high_{};
  double low_key_{};
  double high_key_{};
  std::vector<Record> records_;
  std::uint64_t dropped_{0};
};

}  // namespace hapscene
