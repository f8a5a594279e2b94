#pragma once
// `hapscene run --plot`: the run's time series in a fixed amount of memory, whatever the
// duration. Runs up to kMaxRunTraceRecords ticks are recorded tick by tick (the figure is
// the same as before); longer runs are cut into equal buckets of whole ticks and each
// bucket keeps the two ticks where the commanded force was lowest and highest, in time
// order, so the figure still spans the whole run and no force peak disappears. Every
// record is a real tick. Memory is reserved before the run; on_tick never allocates.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/harness/bucketed_trace.hpp"
#include "engine/harness/recorder.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

inline constexpr std::size_t kMaxRunTraceRecords = 20'000;  // 1.4 MiB of TickRecord

class RunTrace final : public TickObserver {
 public:
  // `planned_ticks`: the run's length (duration x rate); a run that goes longer stops
  // recording and counts the ticks it dropped.
  RunTrace(const SimulationTruth* truth, std::uint64_t planned_ticks)
      : truth_(truth), trace_(planned_ticks, kMaxRunTraceRecords) {}

  void on_tick(const TickState& s) noexcept override { trace_.add(tick_record(s, truth_)); }
  void on_finish(const TickState& /*state*/) override { trace_.finish(); }

  const std::vector<TickRecord>& records() const { return trace_.records(); }
  std::uint64_t ticks_per_bucket() const { return trace_.ticks_per_bucket(); }
  std::uint64_t dropped() const { return trace_.dropped(); }

 private:
  // Each bucket's lowest and highest commanded force.
  struct Keep {
    static double low(const TickRecord& r) noexcept { return r.output_N; }
    static double high(const TickRecord& r) noexcept { return r.output_N; }
  };

  const SimulationTruth* truth_;
  BucketedTrace<TickRecord, Keep> trace_;
};

}  // namespace hapscene
