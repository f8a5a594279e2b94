#pragma once
// `hapscene bench`: the per-tick compute of the loop (sensor pipeline, effects, safety,
// motor command; no I/O) for a scene, next to the hand-written Hapkit lab baseline, on
// the same recorded sensor readings in the same run.
//
// Implementations are compared in many short interleaved rounds: each round times a slice
// of readings of every implementation back to back (in a rotating order), so a slow
// stretch of a shared machine hits them alike and spoils only a few rounds. A median is
// the median over rounds of each round's median; a ratio is the median over rounds of the
// per-round ratio to the group's reference.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/bench/instruction_counter.hpp"
#include "engine/bench/tick_timer.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

// Raw sensor readings of a closed-loop simulated run of `scene` with the sweeping hand:
// realistic inputs, sensor wraps included.
std::vector<std::int32_t> record_sensor_counts(const Scene& scene, double duration_s);

// One implementation of the tick, fed recorded readings.
class TickLoop {
 public:
  virtual ~TickLoop() = default;
  // Ticks counts[begin, end) in timed batches: the median batch's ns per tick.
  virtual double time_slice(TickTimer& timer, const std::vector<std::int32_t>& counts,
                            std::size_t begin, std::size_t end) = 0;
  // `passes` passes with each tick timed alone: the tail fields of `cost`.
  virtual void time_tail(TickTimer& timer, const std::vector<std::int32_t>& counts, int passes,
                         TickCost* cost) = 0;
  // One pass between the counter's start and stop: instructions per tick.
  virtual double instructions_per_tick(InstructionCounter& counter,
                                       const std::vector<std::int32_t>& counts) = 0;
  // Script calls per tick so far (0 for a scene without scripts and for the baseline).
  virtual double script_calls_per_tick() const { return 0.0; }
  // The loop's script instances (null for the baseline): a fault disables one, and the
  // bench must then say so rather than time the 0 N that is left.
  virtual const ScriptList* scripts() const { return nullptr; }
};

// The engine's step() on `scene` (which must outlive the loop), with its own TickState.
std::unique_ptr<TickLoop> scene_tick_loop(const Scene& scene);

// The hand-written baseline for `scene`; null when the scene is not a single lab effect
// (then there is nothing to compare with).
std::unique_ptr<TickLoop> lab_baseline_tick_loop(const Scene& scene);

// The same sketch called out of line through a pointer (as step() is: one call per tick,
// never inlined into the timing loop), and the hand-folded floor (lab_baseline.hpp),
// also out of line; null when the scene is not a single lab effect.
std::unique_ptr<TickLoop> lab_sketch_out_of_line_tick_loop(const Scene& scene);
std::unique_ptr<TickLoop> lab_folded_tick_loop(const Scene& scene);

// Loops compared on the same readings; ratios are against the first.
struct TickLoopGroup {
  const std::vector<std::int32_t>* counts{};
  std::vector<TickLoop*> loops;
};

// Times every loop of every group in interleaved rounds, after 0.3 s of untimed passes:
// a round times one slice of kSliceTicks readings of each loop back to back, in a
// rotating order; `passes` passes over the readings make the rounds. Then each loop's
// tail over `passes` passes. With an available `counter`, one more pass each counts
// instructions. Returns the costs group by group, loop by loop.
inline constexpr std::size_t kSliceTicks = 2048;
std::vector<std::vector<TickCost>> compare_tick_loops(const std::vector<TickLoopGroup>& groups,
                                                      int passes, TickTimer* timer,
                                                      InstructionCounter* counter = nullptr);

}  // namespace hapscene
