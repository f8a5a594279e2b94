#pragma once
// `hapscene bench`'s 2-D rows: the engine's step<2>() on a planar scene next to the
// hand-written 2-D baseline (engine/bench/planar_baseline.hpp), on the same recorded
// readings, timed by compare_tick_loops with the 1-D rows. The loops take an index into
// the recorded readings as their int32 "reading" (a group's counts are 0, 1, ..., n - 1),
// so both implementations pay the same one load per tick.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/bench/planar_baseline.hpp"
#include "engine/bench/tick_bench.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// Each joint's readings of a closed-loop simulated run of `scene` (the profile's simulated
// device, started at its home) with the hand sweeping a raster over the middle 80 % of
// the scene's workspace box, as `run --hand sweep` does.
std::vector<PlanarReading> record_planar_readings(const PlanarScene& scene, double duration_s);

// 0, 1, ..., n - 1: the "counts" a 2-D group hands its loops.
std::vector<std::int32_t> reading_indices(std::size_t n);

// The engine's step<2>() on `scene`; both must outlive the loop.
std::unique_ptr<TickLoop> planar_scene_tick_loop(const PlanarScene& scene,
                                                 const std::vector<PlanarReading>& readings);

// The hand-written baseline for `scene`; null when it is not one inside box on a device
// the baseline is written for (planar_baseline_for).
std::unique_ptr<TickLoop> planar_baseline_tick_loop(const PlanarScene& scene,
                                                    const std::vector<PlanarReading>& readings);

// The engine's step() on a 1-DOF `scene`, fed counts[index] for each index the loop is
// given, so it can share a group (and its rounds) with 2-DOF loops. Both must outlive it.
std::unique_ptr<TickLoop> indexed_scene_tick_loop(const Scene& scene, const std::vector<std::int32_t>& counts);

// A 2-D spring written in Lua, the twin of scripts/spring.lua (F = -K (p - c), as
// `return -K * (s.x - cx), -K * (s.y - cy)`, needing neither velocity nor time): an
// environment's JSON text.
std::string planar_lua_spring_environment(const std::string& name, const std::string& device,
                                          double stiffness_N_per_m, const Vec2& center_m);

// The Lua twin of a scene that is one built-in 2-D spring (same device, safety and rate);
// nothing for any other scene.
std::optional<PlanarScene> planar_lua_equivalent(const PlanarScene& scene);

// A regular polygon of `edges` edges (solid inside, 200 N/m) around the middle of the
// workspace box of `empty` (a scene of the device), radius a fifth of the box's smaller
// side: an environment's JSON text.
std::string regular_polygon_environment(const PlanarScene& empty, const std::string& device, int edges);

}  // namespace hapscene
