#pragma once
// `hapscene run --plot`: the run's time series in a fixed amount of memory, whatever the
// duration. Runs up to kMaxRunTraceRecords ticks are recorded tick by tick (the figure is
// the same as before); longer runs are cut into equal buckets of whole ticks and each
// bucket keeps the two ticks where the commanded force was lowest and highest, in time
// order, so the figure still spans the whole run and no force peak disappears. Every
// record is a real tick. Memory is reserved before the run; on_tick never allocates.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/harness/recorder.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

inline constexpr std::size_t kMaxRunTraceRecords = 20'000;  // 1.4 MiB of TickRecord

class RunTrace final : public TickObserver {
 public:
  // `planned_ticks`: the run's length (duration x rate); a run that goes longer stops
  // recording and counts the ticks it dropped.
  RunTrace(const SimulationTruth* truth, std::uint64_t planned_ticks) : truth_(truth) {
    const std::uint64_t buckets = kMaxRunTraceRecords / 2;
    ticks_per_bucket_ = planned_ticks + 1 <= kMaxRunTraceRecords ? 1 : (planned_ticks + buckets - 1) / buckets;
    records_.reserve(kMaxRunTraceRecords);
  }

  void on_tick(const TickState& s) noexcept override {
    const TickRecord r = tick_record(s, truth_);
    if (ticks_per_bucket_ == 1) {
      push(r);
      return;
    }
    if (in_bucket_ == 0 || r.output_N < low_.output_N) low_ = r;
    if (in_bucket_ == 0 || r.output_N > high_.output_N) high_ = r;
    if (++in_bucket_ == ticks_per_bucket_) close_bucket();
  }

  void on_finish(const TickState& /*state*/) override { close_bucket(); }

  const std::vector<TickRecord>& records() const { return records_; }
  std::uint64_t ticks_per_bucket() const { return ticks_per_bucket_; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  void push(const TickRecord& r) noexcept {
    if (records_.size() == records_.capacity()) {
      ++dropped_;
      return;
    }
    records_.push_back(r);
  }

  // The bucket's lowest and highest force, earlier first (one record when they coincide).
  void close_bucket() noexcept {
    if (in_bucket_ == 0) return;
    const TickRecord& first = low_.t_s <= high_.t_s ? low_ : high_;
    const TickRecord& second = low_.t_s <= high_.t_s ? high_ : low_;
    push(first);
    if (second.t_s != first.t_s) push(second);
    in_bucket_ = 0;
  }

  const SimulationTruth* truth_;
  std::uint64_t ticks_per_bucket_{1};
  std::uint64_t in_bucket_{0};
  TickRecord low_{};
  TickRecord high_{};
  std::vector<TickRecord> records_;
  std::uint64_t dropped_{0};
};

}  // namespace hapscene
