#pragma once
// `hapscene bench`: the per-tick compute of the loop (sensor pipeline, effects, safety,
// motor command; no I/O) for a scene, next to the hand-written Hapkit lab baseline, on
// the same recorded sensor readings in the same run.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/bench/instruction_counter.hpp"
#include "engine/bench/tick_timer.hpp"
#include "engine/core/scene.hpp"

namespace hapscene {

// Raw sensor readings of a closed-loop simulated run of `scene` with the sweeping hand:
// realistic inputs, sensor wraps included.
std::vector<std::int32_t> record_sensor_counts(const Scene& scene, double duration_s);

// The engine's step() over `counts`, `passes` times, each tick timed; with an available
// `counter`, one more pass counts instructions per tick. `script_calls` (optional) gets
// the script calls per tick of that run.
TickCost bench_scene(const Scene& scene, const std::vector<std::int32_t>& counts, int passes,
                     TickTimer* timer, InstructionCounter* counter = nullptr,
                     double* script_calls_per_tick = nullptr);

// The hand-written baseline over the same counts; false when the scene is not a single lab
// effect (then there is no baseline to compare with).
bool bench_lab_baseline(const Scene& scene, const std::vector<std::int32_t>& counts, int passes,
                        TickTimer* timer, TickCost* cost, InstructionCounter* counter = nullptr);

}  // namespace hapscene
