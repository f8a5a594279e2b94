#pragma once
// `hapscene bench`, per device kind: what an environment's rows are timed on (its own
// recorded readings), the hand-written code its rows are compared with, its Lua twin,
// and its goals. bench_command.cpp is written once over N: it loads each file once,
// builds every environment's rows through these overloads, times every group in one
// interleaved run and prints one table per kind. bench_capstan.cpp has the 1-DOF kind's
// (the lab sketch's rows), bench_planar.cpp the 2-DOF kind's (the course code's). A new
// kind adds its overloads and its BenchKindOf in a file of its own.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/bench/planar_tick_bench.hpp"
#include "engine/bench/tick_bench.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// One timed row of a table.
struct BenchRow {
  const char* label;
  std::unique_ptr<TickLoop> loop;
  bool tail_goal{};  // a row that runs scripts: p99.9 at most kBenchTailGoalRatio x its median
};

// Lua rows: p99.9 against the median (no GC spikes).
inline constexpr double kBenchTailGoalRatio = 5.0;

// What a kind's loops are fed: `feed` is what the group hands every loop (the 1-D sensor
// counts themselves; in 2-D, indices into `readings`, so every loop pays one load a tick).
template <int N>
struct BenchFeedOf;
template <>
struct BenchFeedOf<1> {
  std::vector<std::int32_t> feed;
};
template <>
struct BenchFeedOf<2> {
  std::vector<PlanarReading> readings;
  std::vector<std::int32_t> feed;
};

// One environment's group: its rows on its own readings, the kind's hand-written code first
// when there is one for the scene (the ratios' reference; without it no ratio is printed),
// then the engine on the scene, then its Lua twin (and the twin with the VM alone when
// its force is translated). Loops point into it: it is built in place and never moved.
template <int N>
struct BenchEnvironmentOf {
  SceneOf<N> scene;
  BenchFeedOf<N> feed;
  std::optional<SceneOf<N>> lua, lua_vm;
  std::vector<BenchRow> rows;
  std::size_t references{};  // rows of hand-written code, first
  std::optional<std::size_t> lua_row;
  std::size_t engine_row() const { return references; }
};

// Per kind: the table's name column, the files a bench times by default, and what bounds
// a run's memory (the most rows of hand-written code an environment has; the bytes a tick
// of its recording takes, feed included, in 4-byte readings).
template <int N>
struct BenchKindOf;
template <>
struct BenchKindOf<1> {
  static constexpr int kNameWidth = 10;
  static constexpr std::size_t kReferenceRows = 3;
  static constexpr double kReadingWeight = 1.0;
  static const char* const kDefaultFiles[4];
};
template <>
struct BenchKindOf<2> {
  static constexpr int kNameWidth = 24;
  static constexpr std::size_t kReferenceRows = 1;
  static constexpr double kReadingWeight = (static_cast<double>(sizeof(PlanarReading)) + 4.0) / 4.0;
  static const char* const kDefaultFiles[3];
};

// The readings of a closed-loop simulated run of `scene` with the hand sweeping its workspace.
BenchFeedOf<1> record_bench_feed(const SceneOf<1>& scene, double seconds);
BenchFeedOf<2> record_bench_feed(const SceneOf<2>& scene, double seconds);

// The engine's step<N>() on `scene` fed `feed` (both must outlive the loop).
std::unique_ptr<TickLoop> engine_tick_loop(const SceneOf<1>& scene, const BenchFeedOf<1>& feed);
std::unique_ptr<TickLoop> engine_tick_loop(const SceneOf<2>& scene, const BenchFeedOf<2>& feed);

// The hand-written code's rows for `scene` (none when there is none for it): 1-D, the
// hand-folded floor and the lab's sketch inlined and called; 2-D, the course code.
std::vector<BenchRow> reference_rows(const SceneOf<1>& scene, const BenchFeedOf<1>& feed);
std::vector<BenchRow> reference_rows(const SceneOf<2>& scene, const BenchFeedOf<2>& feed);

// The scene written as a Lua script, when it is one the kind knows how to translate (1-D:
// a single lab effect, with the shipped scripts in `scripts_dir`; 2-D: one spring).
std::optional<SceneOf<1>> lua_twin(const SceneOf<1>& scene, const std::string& scripts_dir);
std::optional<SceneOf<2>> lua_twin(const SceneOf<2>& scene, const std::string& scripts_dir);

// The kind's goals for one environment's measured rows (`costs` in row order, the ratios
// against the reference already blanked without one), as lines for the goals list;
// `defaults`: the bench runs its default environments.
void add_bench_goals(const BenchEnvironmentOf<1>& environment, const std::vector<TickCost>& costs, bool defaults,
                     std::vector<std::string>* goals);
void add_bench_goals(const BenchEnvironmentOf<2>& environment, const std::vector<TickCost>& costs, bool defaults,
                     std::vector<std::string>* goals);

// The 2-D rows a default bench adds after the files: a polygon of kBenchPolygonEdges edges
// on the Haplink (its median has a goal of its own).
inline constexpr int kBenchPolygonEdges = 1000;
inline constexpr const char* kBenchPolygonDevice = "haplink";
SceneOf<2> bench_polygon_scene();

}  // namespace hapscene
