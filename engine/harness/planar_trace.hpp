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
#include "engine/harness/bucketed_trace.hpp"
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
      : truth_(truth), proxy_index_(proxy_index), trace_(planned_ticks, kMaxPlanarTraceRecords) {}

  void on_tick(const TickStateOf<2>& s) noexcept override { trace_.add(record(s)); }
  void on_finish(const TickStateOf<2>& /*state*/) override { trace_.finish(); }

  const std::vector<PlanarTickRecord>& records() const { return trace_.records(); }
  std::uint64_t ticks_per_bucket() const { return trace_.ticks_per_bucket(); }
  std::uint64_t dropped() const { return trace_.dropped(); }
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

  // Each bucket's first tick and its largest force magnitude.
  struct Keep {
    static double low(const PlanarTickRecord& r) noexcept { return r.t_s; }
    static double high(const PlanarTickRecord& r) noexcept { return norm(r.output_N); }
  };

  const SimulationTruthOf<2>* truth_;
  int proxy_index_;
  BucketedTrace<PlanarTickRecord, Keep> trace_;
};

}  // namespace hapscene
