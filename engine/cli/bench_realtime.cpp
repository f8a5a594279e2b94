// `hapscene bench --realtime [ENV...] [--seconds S]`: the tick measured the way the real
// 1 kHz loop runs it: sleep to shortly before each deadline, wake, tick, with the
// compute timed as `run` times it (the summary's compute figures). Each environment, as
// built-in JSON effects and as its Lua twin, three ways on the same recorded readings:
//   hot   ticks back to back (caches and predictors warm: the tick-cost table's case)
//   cold  the real loop without warming: sleep, wake, tick
//   warm  the real loop as `run` does it: the spin before the deadline replays the last
//         tick dry, warming its code and data (engine/run/warm_tick.hpp)
#include <sys/prctl.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "engine/base/clock.hpp"
#include "engine/bench/build_info.hpp"
#include "engine/bench/lua_equivalent.hpp"
#include "engine/bench/tick_bench.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/realtime.hpp"
#include "engine/run/warm_tick.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

constexpr double kBuiltinWarmP50Goal_ns = 100.0;
constexpr double kLuaSpringWarmP50Goal_ns = 300.0;
constexpr double kLuaSpringWarmP99Goal_ns = 2000.0;

struct Percentiles {
  double p50_ns{};
  double p99_ns{};
};

Percentiles percentiles_of(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  const auto at = [&](double q) { return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))]; };
  return {at(0.5), at(0.99)};
}

enum class CacheState { hot, cold, warm };

// One pass over the readings with a fresh state: each tick's compute (step() between two
// clock reads, as the runner times it), paced as asked.
Percentiles time_ticks(const Scene& scene, const std::vector<std::int32_t>& counts, CacheState pacing) {
  TickState state = make_tick_state(scene);
  std::vector<double> compute_ns;
  compute_ns.reserve(counts.size());
  const auto period_ns = static_cast<std::int64_t>(scene.period_s * 1e9);
  TickWarmer warmer(scene);
  std::int64_t deadline_ns = monotonic_now_ns() + period_ns;
  for (const std::int32_t raw : counts) {
    if (pacing == CacheState::cold) wait_until(monotonic_loop_clock(), deadline_ns, [] {});
    if (pacing == CacheState::warm) wait_until(monotonic_loop_clock(), deadline_ns, [&] { warmer.warm(scene, state); });
    warmer.note_reading(raw);
    const std::int64_t begin_ns = monotonic_now_ns();
    step(scene, raw, &state);
    const std::int64_t end_ns = monotonic_now_ns();
    compute_ns.push_back(static_cast<double>(end_ns - begin_ns));
    collect_script_garbage(&state);
    deadline_ns += period_ns;
    if (monotonic_now_ns() > deadline_ns) deadline_ns = monotonic_now_ns() + period_ns;  // realign after a stall
  }
  for (const auto& script : state.scripts) {
    if (script->disabled()) std::fprintf(stderr, "%s (while timing %s)\n", std::string(script->fault_message()).c_str(), scene.name.c_str());
  }
  return percentiles_of(std::move(compute_ns));
}

}  // namespace

int bench_realtime(Arguments& arguments) {
  const double seconds = arguments.take(option::bench_seconds).value_or(1.0);
  const std::string scripts_dir = arguments.take_value("scripts").value_or("scripts");
  std::vector<std::string> files = arguments.positionals();
  if (files.empty()) {
    files = {"environments/spring.json", "environments/wall.json", "environments/damper.json",
             "environments/texture.json"};
  }
  struct Row {
    Scene scene;
    const char* implementation;
    std::vector<std::int32_t> counts;
    std::string environment;  // the file's scene name (the Lua twin's is another)
  };
  std::vector<Row> rows;
  for (const std::string& file : files) {
    Scene scene = load_environment_file(file);
    std::vector<std::int32_t> counts = record_sensor_counts(scene, seconds);
    std::optional<Scene> lua = lua_equivalent(scene, scripts_dir);
    const char* label = scene.script_count > 0 ? "Lua script" : "built-in (JSON)";
    const std::string name = scene.name;
    rows.push_back(Row{std::move(scene), label, counts, name});
    if (lua) rows.push_back(Row{std::move(*lua), "Lua script", std::move(counts), name});
  }

  // The loop's conditions: exact wake-ups, real-time scheduling when permitted.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  const RealtimeGuard realtime(true);
  print_out("build: %s\n", build_description().c_str());
  print_out("real-time tick: compute per tick in ns as `run` times it, %g s of recorded readings per row and "
            "pacing; hot = back to back, cold = sleep, wake, tick; warm = the same with the spin before the deadline "
            "replaying the last tick dry to warm its code and data (what `run` does)\n", seconds);
  print_out("%s\n\n", realtime.note().c_str());
  print_out("%-10s %-16s %8s %8s %9s %9s %9s %9s\n", "environment", "implementation", "hot_p50", "hot_p99", "cold_p50",
            "cold_p99", "warm_p50", "warm_p99");
  std::vector<std::string> goals;
  char goal[200];
  for (const Row& row : rows) {
    const Percentiles hot = time_ticks(row.scene, row.counts, CacheState::hot);
    const Percentiles cold = time_ticks(row.scene, row.counts, CacheState::cold);
    const Percentiles warm = time_ticks(row.scene, row.counts, CacheState::warm);
    print_out("%-10s %-16s %8.0f %8.0f %9.0f %9.0f %9.0f %9.0f\n", row.environment.c_str(), row.implementation,
              hot.p50_ns, hot.p99_ns, cold.p50_ns, cold.p99_ns, warm.p50_ns, warm.p99_ns);
    flush_out();
    const bool lua = row.scene.script_count > 0;
    if (!lua) {
      std::snprintf(goal, sizeof goal, "%s built-in: warm p50 %.0f ns (goal <= %.0f ns): %s", row.environment.c_str(),
                    warm.p50_ns, kBuiltinWarmP50Goal_ns, warm.p50_ns <= kBuiltinWarmP50Goal_ns ? "met" : "NOT met");
      goals.push_back(goal);
    } else if (row.environment == "spring") {
      const bool met = warm.p50_ns <= kLuaSpringWarmP50Goal_ns && warm.p99_ns <= kLuaSpringWarmP99Goal_ns;
      std::snprintf(goal, sizeof goal, "spring Lua: warm p50 %.0f ns, p99 %.0f ns (goals <= %.0f ns, <= %.0f ns): %s",
                    warm.p50_ns, warm.p99_ns, kLuaSpringWarmP50Goal_ns, kLuaSpringWarmP99Goal_ns, met ? "met" : "NOT met");
      goals.push_back(goal);
    }
  }
  print_out("\ngoals\n");
  for (const std::string& line : goals) print_out("  %s\n", line.c_str());
  return 0;
}

}  // namespace hapscene
