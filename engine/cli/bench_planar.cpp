// `hapscene bench` for the 2-DOF kind (engine/cli/bench_kind.hpp): rows against the
// course's hand-written 2-D code, a 2-D spring's Lua twin, the generated polygon, and
// their goals.
#include <cstdio>

#include "engine/cli/bench_kind.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

constexpr double kPlanarBoxGoalRatio = 1.5;   // built-in 2-D boxes against the hand-written course code
constexpr double kPolygonGoal_ns = 1000.0;    // the generated polygon, median per tick

std::string polygon_name() { return "polygon_" + std::to_string(kBenchPolygonEdges); }

}  // namespace

// The course's inside box on both devices (against the hand-written 2-D code) and a
// round cage.
const char* const BenchKindOf<2>::kDefaultFiles[3] = {"environments/planar/haplink_box_inside.json",
                                                      "environments/planar/haply2diy_v3_box_inside.json",
                                                      "environments/planar/haplink_circle_outside.json"};

BenchFeedOf<2> record_bench_feed(const SceneOf<2>& scene, double seconds) {
  BenchFeedOf<2> out;
  out.readings = record_planar_readings(scene, seconds);
  out.feed = reading_indices(out.readings.size());
  return out;
}

std::unique_ptr<TickLoop> engine_tick_loop(const SceneOf<2>& scene, const BenchFeedOf<2>& feed) {
  return planar_scene_tick_loop(scene, feed.readings);
}

std::vector<BenchRow> reference_rows(const SceneOf<2>& scene, const BenchFeedOf<2>& feed) {
  std::vector<BenchRow> rows;
  std::unique_ptr<TickLoop> course = planar_baseline_tick_loop(scene, feed.readings);
  if (course) rows.push_back({"hand-written C++", std::move(course)});
  return rows;
}

std::optional<SceneOf<2>> lua_twin(const SceneOf<2>& scene, const std::string& /*scripts_dir*/) {
  return planar_lua_equivalent(scene);
}

void add_bench_goals(const BenchEnvironmentOf<2>& environment, const std::vector<TickCost>& costs, bool defaults,
                     std::vector<std::string>* goals) {
  const std::string& name = environment.scene.name;
  const TickCost& builtin = costs[environment.engine_row()];
  char goal[320];
  if (environment.references > 0) {
    std::snprintf(goal, sizeof goal, "%s: built-in %.2fx the hand-written code (goal <= %.1fx): %s", name.c_str(),
                  builtin.ratio, kPlanarBoxGoalRatio, builtin.ratio <= kPlanarBoxGoalRatio ? "met" : "NOT met");
    goals->push_back(goal);
  }
  if (defaults && name == polygon_name()) {
    std::snprintf(goal, sizeof goal, "%s: built-in median %.1f ns (goal < %.0f ns): %s", name.c_str(),
                  builtin.median_ns, kPolygonGoal_ns, builtin.median_ns < kPolygonGoal_ns ? "met" : "NOT met");
    goals->push_back(goal);
  }
}

SceneOf<2> bench_polygon_scene() {
  const PlanarScene empty = load_planar_environment_text(
      std::string(R"({"device": ")") + kBenchPolygonDevice + R"(", "effects": []})", "bench");
  return load_planar_environment_text(regular_polygon_environment(empty, kBenchPolygonDevice, kBenchPolygonEdges),
                                      "bench");
}

}  // namespace hapscene
