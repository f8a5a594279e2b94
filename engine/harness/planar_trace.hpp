#pragma once
// A 2-DOF run's trace for its figure (`plot` and `run --plot` on a planar scene): per kept
// tick the handle (true and measured), one shape's proxy, the force asked for, commanded
// and the hand's, in a fixed amount of memory whatever the run's length. Runs up to
// kMaxPlanarTraceRecords ticks are kept tick by tick; longer runs are cut into equal
// buckets of whole ticks and each bucket keeps its first tick (so the paths are sampled
// evenly) and the tick of its largest commanded force magnitude (so no force peak
// disappears), in time order. Every record is a real tick. Memory is reserved before the
// run; on_tick never allocates.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/devices/device.hpp"
#include "engine/run/tick_observer.hpp"

namespace hapscene {

inline constexpr std::size_t kMaxPlanarTraceRecords = 20'000;  // 2.0 MiB of PlanarTickRecord (104 bytes)

struct PlanarTickRecord {
  double t_s{};
  Vec2 x_true_m{};        // the simulator's handle (the measured one without a simulator)
  Vec2 x_m{};             // what the host measured
  Vec2 proxy_m{};         // the traced shape's proxy (the handle when no shape is traced)
  Vec2 requested_N{};     // sum of the effects
  Vec2 output_N{};        // after safety
  Vec2 hand_N{};          // the hand's force on the handle (0 without a simulator)
};

class PlanarTrace final : public TickObserverOf<2> {
 public:
  // `planned_ticks`: the run's length (duration x rate); a run that goes longer stops
  // recording and counts the ticks it dropped. `proxy_index`: which of the run's shape
  // proxies to record (TickStateOf<2>::effect_runs, in the bank's order), or -1 for none.
  PlanarTrace(const SimulationTruthOf<2>* truth, std::uint64_t planned_ticks, int proxy_index)
      : truth_(truth), proxy_index_(proxy_index) {
    const std::uint64_t buckets = kMaxPlanarTraceRecords / 2;
    ticks_per_bucket_ =
        planned_ticks + 1 <= kMaxPlanarTraceRecords ? 1 : (planned_ticks + buckets - 1) / buckets;
    records_.reserve(kMaxPlanarTraceRecords);
  }

  void on_tick(const TickStateOf<2>& s) noexcept override {
    const PlanarTickRecord r = record(s);
    if (ticks_per_bucket_ == 1) {
      push(r);
      return;
    }
    if (in_bucket_ == 0) first_ = r;
    const double magnitude = norm(r.output_N);
    if (in_bucket_ == 0 || magnitude > peak_magnitude_) {
      peak_ = r;
      peak_magnitude_ = magnitude;
    }
    if (++in_bucket_ == ticks_per_bucket_) close_bucket();
  }

  void on_finish(const TickStateOf<2>& /*state*/) override { close_bucket(); }

  const std::vector<PlanarTickRecord>& records() const { return records_; }
  std::uint64_t ticks_per_bucket() const { return ticks_per_bucket_; }
  std::uint64_t dropped() const { return dropped_; }
  int proxy_index() const { return proxy_index_; }

 private:
  PlanarTickRecord record(const TickStateOf<2>& s) const noexcept {
    PlanarTickRecord r;
    r.t_s = s.t_s;
    r.x_m = s.x_m;
    r.x_true_m = truth_ != nullptr ? truth_->x_m() : s.x_m;
    r.hand_N = truth_ != nullptr ? truth_->hand_force_N() : Vec2{};
    const auto index = static_cast<std::size_t>(proxy_index_);
    r.proxy_m = proxy_index_ >= 0 && index < s.effect_runs.size() ? s.effect_runs[index].proxy_m : s.x_m;
    r.requested_N = s.effects_force_N;
    r.output_N = s.output_N;
    return r;
  }

  void push(const PlanarTickRecord& r) noexcept {
    if (records_.size() == records_.capacity()) {
      ++dropped_;
      return;
    }
    records_.push_back(r);
  }

  // The bucket's first tick and its peak, earlier first (one record when they coincide).
  void close_bucket() noexcept {
    if (in_bucket_ == 0) return;
    push(first_);
    if (peak_.t_s != first_.t_s) push(peak_);
    in_bucket_ = 0;
  }

  const SimulationTruthOf<2>* truth_;
  int proxy_index_;
  std::uint64_t ticks_per_bucket_{1};
  std::uint64_t in_bucket_{0};
  PlanarTickRecord first_{};
  PlanarTickRecord peak_{};
  double peak_magnitude_{};
  std::vector<PlanarTickRecord> records_;
  std::uint64_t dropped_{0};
};

}  // namespace hapscene
