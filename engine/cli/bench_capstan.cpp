// `hapscene bench` for the 1-DOF kind (engine/cli/bench_kind.hpp): rows against the lab's
// sketch, the shipped scripts as the Lua twins, and the goals of the lab's rows.
#include <cstdio>

#include "engine/bench/lua_equivalent.hpp"
#include "engine/cli/bench_kind.hpp"

namespace hapscene {
namespace {

// Built-in 1-D effects against the lab's sketch called out of line (the like-for-like row:
// the engine's step() is called out of line too); the hand-folded floor is printed as the
// ratios' reference, without a verdict (it has no safety stage and a simpler flip counter).
constexpr double kBuiltinSketchGoalRatio = 1.0;
constexpr std::size_t kSketchCallRow = 2;     // among the reference rows
constexpr double kLuaGoal_ns = 150.0;         // Lua scripts, median per tick
constexpr double kLuaSpringGoal_ns = 50.0;    // scripts/spring.lua, median per tick (at most)
constexpr double kLuaTextureGoal_ns = 70.0;   // scripts/texture.lua, median per tick (under)

}  // namespace

const char* const BenchKindOf<1>::kDefaultFiles[4] = {"environments/spring.json", "environments/wall.json",
                                                      "environments/damper.json", "environments/texture.json"};

BenchFeedOf<1> record_bench_feed(const SceneOf<1>& scene, double seconds) {
  return {record_sensor_counts(scene, seconds)};
}

std::unique_ptr<TickLoop> engine_tick_loop(const SceneOf<1>& scene, const BenchFeedOf<1>& /*feed*/) {
  return scene_tick_loop(scene);
}

std::vector<BenchRow> reference_rows(const SceneOf<1>& scene, const BenchFeedOf<1>& /*feed*/) {
  std::vector<BenchRow> rows;
  std::unique_ptr<TickLoop> floor = lab_folded_tick_loop(scene);
  if (!floor) return rows;
  rows.push_back({"hand-folded floor", std::move(floor)});
  rows.push_back({"sketch, inlined", lab_baseline_tick_loop(scene)});
  rows.push_back({"sketch, call", lab_sketch_out_of_line_tick_loop(scene)});
  return rows;
}

std::optional<SceneOf<1>> lua_twin(const SceneOf<1>& scene, const std::string& scripts_dir) {
  return lua_equivalent(scene, scripts_dir);
}

void add_bench_goals(const BenchEnvironmentOf<1>& environment, const std::vector<TickCost>& costs, bool defaults,
                     std::vector<std::string>* goals) {
  const std::string& name = environment.scene.name;
  char goal[240];
  if (environment.references > 0) {
    const double sketch_call_ns = costs[kSketchCallRow].median_ns;
    const double builtin_ns = costs[environment.engine_row()].median_ns;
    const bool measured = sketch_call_ns > 0.0 && builtin_ns > 0.0;
    const double ratio = measured ? builtin_ns / sketch_call_ns : 0.0;
    std::snprintf(goal, sizeof goal, "%s: built-in %.2fx the lab sketch called out of line (goal <= %.1fx): %s",
                  name.c_str(), ratio, kBuiltinSketchGoalRatio,
                  !measured ? "not measured" : ratio <= kBuiltinSketchGoalRatio ? "met" : "NOT met");
    goals->push_back(goal);
  }
  if (!environment.lua_row) return;
  const double lua_ns = costs[*environment.lua_row].median_ns;
  std::snprintf(goal, sizeof goal, "%s: Lua median %.1f ns (goal < %.0f ns): %s", name.c_str(), lua_ns, kLuaGoal_ns,
                lua_ns < kLuaGoal_ns ? "met" : "NOT met");
  goals->push_back(goal);
  // The shipped spring and texture scripts have goals of their own.
  if (defaults && (name == "spring" || name == "texture")) {
    const bool spring_row = name == "spring";
    const double limit_ns = spring_row ? kLuaSpringGoal_ns : kLuaTextureGoal_ns;
    const bool met = spring_row ? lua_ns <= limit_ns : lua_ns < limit_ns;
    std::snprintf(goal, sizeof goal, "%s: Lua median %.1f ns (goal %s %.0f ns): %s", name.c_str(), lua_ns,
                  spring_row ? "<=" : "<", limit_ns, met ? "met" : "NOT met");
    goals->push_back(goal);
  }
}

}  // namespace hapscene
