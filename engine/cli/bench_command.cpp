// `hapscene bench [ENV...]`: per-tick compute cost of each environment next to the
// hand-written code of its kind (the Hapkit lab's sketch, the 2-D course code), and a table
// of what each part of a scene costs, all measured in one run so the ratios compare like
// with like. Written once over N: what differs per device kind is in bench_kind.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <variant>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/bench/build_info.hpp"
#include "engine/bench/instruction_counter.hpp"
#include "engine/bench/planar_tick_bench.hpp"
#include "engine/bench/script_call_bench.hpp"
#include "engine/bench/tick_bench.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/bench_kind.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

// Scenes that differ in one part only: the difference in cost is that part's cost.
constexpr const char* kPartScenes[][2] = {
    {"no effect (sensor, safety, command)", R"({"effects": []})"},
    {"spring", R"({"effects": [{"type": "spring", "stiffness": 100}]})"},
    {"spring + 10 disabled effects", R"({"effects": [{"type": "spring", "stiffness": 100},
      {"type": "damper", "damping": 1, "enabled": false}, {"type": "damper", "damping": 1, "enabled": false},
      {"type": "damper", "damping": 1, "enabled": false}, {"type": "damper", "damping": 1, "enabled": false},
      {"type": "damper", "damping": 1, "enabled": false}, {"type": "texture", "width": 0.005, "damping": 1, "enabled": false},
      {"type": "texture", "width": 0.005, "damping": 1, "enabled": false}, {"type": "wall", "position": 0, "stiffness": 1, "solid": "above", "enabled": false},
      {"type": "wall", "position": 0, "stiffness": 1, "solid": "above", "enabled": false}, {"type": "wall", "position": 0, "stiffness": 1, "solid": "above", "enabled": false}]})"},
    {"spring + 10 effects that cannot act in the workspace", R"({"effects": [{"type": "spring", "stiffness": 100},
      {"type": "wall", "position": 1, "stiffness": 500, "solid": "above"}, {"type": "wall", "position": 2, "stiffness": 500, "solid": "above"},
      {"type": "wall", "position": 3, "stiffness": 500, "solid": "above"}, {"type": "wall", "position": -1, "stiffness": 500, "solid": "below"},
      {"type": "wall", "position": -2, "stiffness": 500, "solid": "below"}, {"type": "wall", "position": -3, "stiffness": 500, "solid": "below"},
      {"type": "damper", "damping": 0}, {"type": "damper", "damping": 0},
      {"type": "texture", "width": 0.005, "damping": 0}, {"type": "spring", "stiffness": 0}]})"},
    {"damper (adds the velocity estimator)", R"({"effects": [{"type": "damper", "damping": 1}]})"},
    {"texture, 10 fields over the workspace", R"({"effects": [{"type": "texture", "width": 0.005, "damping": 1}]})"},
    {"texture, 10000 fields over the workspace", R"({"effects": [{"type": "texture", "width": "5 um", "damping": 1}]})"},
    {"texture, 50000 fields of 1 um (the finest)", R"({"effects": [{"type": "texture", "width": "1 um", "damping": 1}]})"},
    {"10 built-in effects", R"({"effects": [{"type": "spring", "stiffness": 10}, {"type": "spring", "stiffness": 10},
      {"type": "damper", "damping": 0.1}, {"type": "damper", "damping": 0.1}, {"type": "texture", "width": 0.005, "damping": 0.1},
      {"type": "texture", "width": 0.004, "damping": 0.1}, {"type": "wall", "position": 0.02, "stiffness": 100, "solid": "above"},
      {"type": "wall", "position": -0.02, "stiffness": 100, "solid": "below"}, {"type": "wall", "position": 0.03, "stiffness": 100, "solid": "above"},
      {"type": "wall", "position": -0.03, "stiffness": 100, "solid": "below"}]})"},
    {"spring as a Lua script (scripts/spring.lua)", R"({"effects": [{"type": "script", "file": "scripts/spring.lua"}]})"},
    {"one Lua script + 10 built-in effects", R"({"effects": [{"type": "script", "file": "scripts/spring.lua",
      "params": {"stiffness": 10}}, {"type": "spring", "stiffness": 10}, {"type": "spring", "stiffness": 10},
      {"type": "damper", "damping": 0.1}, {"type": "damper", "damping": 0.1}, {"type": "texture", "width": 0.005, "damping": 0.1},
      {"type": "texture", "width": 0.004, "damping": 0.1}, {"type": "wall", "position": 0.02, "stiffness": 100, "solid": "above"},
      {"type": "wall", "position": -0.02, "stiffness": 100, "solid": "below"}, {"type": "wall", "position": 0.03, "stiffness": 100, "solid": "above"},
      {"type": "wall", "position": -0.03, "stiffness": 100, "solid": "below"}]})"},
};

constexpr double kTextureFieldsGoalRatio = 1.1;  // texture at 50 000 fields (the finest) against 10 fields
// The parts rows the texture goal compares (indices into kPartScenes).
constexpr std::size_t kTexture10Part = 5;
constexpr std::size_t kTextureFinestPart = 7;
// The 2-D Lua spring's force call against the 1-D one's, per returned value (it returns
// two); the whole ticks' ratio is printed without a verdict (the 2-D tick also runs the
// linkage's kinematics).
constexpr double kLuaPlanarPerValueGoalRatio = 1.0;

// A kind's environments, each built in place (their loops point into them).
template <int N>
using BenchEnvironmentsOf = std::vector<std::unique_ptr<BenchEnvironmentOf<N>>>;

// Calls f on each kind's environments, in the order of the list of N.
template <class Kinds, class F>
void for_each_kind(Kinds& kinds, F f) {
  std::apply([&](auto&... kind) { (f(kind), ...); }, kinds);
}

// What a row of the engine runs: built-in effects only, scripts only (a .lua environment,
// or JSON made of script effects), or both.
template <int N>
const char* implementation_label(const SceneOf<N>& scene) {
  if (scene.script_count == 0) return "built-in (JSON)";
  if (scene.script_count == scene.effects.size()) return "Lua script";
  return "built-in + Lua";
}

// Whether a loop's scripts run a translated force (then a VM-only row shows the difference).
bool runs_translated(const TickLoop& loop) {
  if (loop.scripts() == nullptr) return false;
  for (const auto& script : *loop.scripts()) {
    if (script->force_translated()) return true;
  }
  return false;
}

// An environment of N axes: its Lua twin found now (the memory check counts its rows),
// its rows built once every file has loaded.
template <int N>
void add_environment(SceneOf<N> scene, const std::string& scripts_dir, BenchEnvironmentsOf<N>* environments) {
  auto environment = std::make_unique<BenchEnvironmentOf<N>>();
  environment->scene = std::move(scene);
  environment->lua = lua_twin(environment->scene, scripts_dir);
  environments->push_back(std::move(environment));
}

// The environments a bench run times, per kind; every file is loaded (once) before
// anything is recorded.
struct BenchScenes {
  AxesTuple<BenchEnvironmentsOf> kinds;
  std::size_t count() {
    std::size_t n = 0;
    for_each_kind(kinds, [&](const auto& environments) { n += environments.size(); });
    return n;
  }
};

void load_bench_scenes(const std::vector<std::string>& files, bool defaults, const std::string& scripts_dir,
                       BenchScenes* b) {
  for (const std::string& file : files) {
    AnyEnvironment loaded = load_any_environment(file);
    std::visit(
        [&](auto& environment) {
          constexpr int N = std::remove_cvref_t<decltype(environment)>::kAxes;
          add_environment(std::move(environment.scene), scripts_dir, &axes_get<N>(b->kinds));
        },
        loaded);
  }
  if (defaults) add_environment(bench_polygon_scene(), scripts_dir, &axes_get<2>(b->kinds));
}

// The memory the values drive, estimated before anything is recorded: the recorded
// readings (4-byte readings a tick, BenchKindOf<N>::kReadingWeight of them per kind), two
// timings per round for every loop (rounds = passes x slices of the longest recording)
// and one timing per tick of the tail measurement (readings x passes / kTailRepeats, the
// longest loop at a time). Over kMaxBenchBytes the command is refused, naming the values
// to lower.
constexpr double kMaxBenchBytes = 1024.0 * 1024.0 * 1024.0;  // 1 GiB

std::string mebibytes(double bytes) { return format_number(std::round(bytes / (1024.0 * 1024.0))) + " MiB"; }

void check_bench_memory(const Arguments& arguments, BenchScenes& b, bool defaults, double seconds, int passes) {
  double longest_ticks = std::floor(seconds * 1000.0);  // the parts group runs at the default 1 kHz
  double readings = longest_ticks;
  double loops = static_cast<double>(std::size(kPartScenes));
  for_each_kind(b.kinds, [&](const auto& environments) {
    for (const auto& environment : environments) {
      using Kind = BenchKindOf<std::remove_cvref_t<decltype(environment->scene)>::kAxes>;
      const double ticks = std::floor(seconds * environment->scene.rate_hz);
      readings += Kind::kReadingWeight * ticks;
      longest_ticks = std::max(longest_ticks, ticks);
      // The kind's hand-written rows at most, the engine's, and the twin's two.
      loops += static_cast<double>(Kind::kReferenceRows) + 1.0 + (environment->lua ? 2.0 : 0.0);
    }
  });
  // The default rows add the Lua spring in 1-D and 2-D: a 2-D recording and six loops.
  if (defaults) {
    readings += BenchKindOf<2>::kReadingWeight * std::floor(seconds * 1000.0);
    loops += 6.0;
  }
  const double slices = std::max(1.0, std::floor(longest_ticks / static_cast<double>(kSliceTicks)));
  const double readings_bytes = 4.0 * readings;
  const double rounds_bytes = 2.0 * 8.0 * static_cast<double>(passes) * slices * loops;
  const double tail_bytes = 8.0 * longest_ticks * static_cast<double>(passes) / static_cast<double>(TickTimer::kTailRepeats);
  const double total = readings_bytes + rounds_bytes + tail_bytes;
  if (total > kMaxBenchBytes) {
    arguments.fail("--seconds " + format_number(seconds) + " x --passes " + std::to_string(passes) + " over " +
                   std::to_string(b.count()) + " environment(s) needs about " + mebibytes(total) +
                   " (readings " + mebibytes(readings_bytes) + ", round timings " + mebibytes(rounds_bytes) +
                   ", tail timings " + mebibytes(tail_bytes) + "), more than the " + mebibytes(kMaxBenchBytes) +
                   " a bench may use; lower --seconds or --passes, or give fewer environments");
  }
}

void print_preamble(double seconds, int passes, const InstructionCounter& counter) {
  print_out("build: %s\n", build_description().c_str());
  print_out("tick compute in ns (read counts -> motor command, no I/O); %g s of recorded sensor "
            "readings x %d passes per row, every row interleaved in rounds of %zu ticks; ratios against the "
            "hand-folded floor, same rounds\n", seconds, passes, kSliceTicks);
  print_out("rows: hand-folded floor = the lab tick with constants folded, no division, called out of line; "
            "sketch = the lab's sketch as written (velocity filter every loop), inlined into the timing loop, "
            "and called out of line like the engine's step()\n");
  if (counter.available()) {
    print_out("instr: instructions per tick from the CPU's counters (one more pass)\n\n");
  } else {
    print_out("instr: not available here (%s); count them with valgrind: hapscene bench --callgrind "
              "(see docs/explanation/measurements.md)\n\n", counter.reason().c_str());
  }
}

// An environment's rows, on its own recording: the kind's hand-written code, the engine,
// the Lua twin and the twin in the VM alone.
template <int N>
void build_rows(double seconds, BenchEnvironmentOf<N>* e) {
  e->feed = record_bench_feed(e->scene, seconds);
  e->rows = reference_rows(e->scene, e->feed);
  e->references = e->rows.size();
  e->rows.push_back({implementation_label(e->scene), engine_tick_loop(e->scene, e->feed), e->scene.script_count > 0});
  if (!e->lua) return;
  e->lua_row = e->rows.size();
  e->rows.push_back({"Lua script", engine_tick_loop(*e->lua, e->feed), true});
  if (runs_translated(*e->rows.back().loop)) {
    e->lua_vm = with_scripts_in_vm(*e->lua);
    e->rows.push_back({"Lua, VM only", engine_tick_loop(*e->lua_vm, e->feed), false});
  }
}

// The Lua spring in 1-D (the spring row's Lua twin on its readings) and in 2-D (on the
// Haplink, its own readings), in one group of indices into both recordings; then the
// force calls alone, as they run and in the VM alone, a group each (1-D first).
struct LuaSpringLoops {
  std::optional<PlanarScene> planar;
  std::vector<PlanarReading> planar_readings;
  std::vector<std::int32_t> indices;
  std::unique_ptr<TickLoop> one_axis, two_axes;
  std::unique_ptr<TickLoop> calls[4];  // the force calls alone: 1-D, 2-D; then both in the VM alone
  std::size_t group = 0;
  std::size_t call_group = 0;
};

// Everything one run times, in groups interleaved in one measurement. The groups point
// into this object, so it is built in place and never moved.
struct BenchLoops {
  BenchLoops() = default;
  BenchLoops(const BenchLoops&) = delete;
  BenchLoops& operator=(const BenchLoops&) = delete;

  // Each environment's group, kind by kind, where `first_group` says.
  std::size_t first_group[std::tuple_size_v<AxesTuple<BenchEnvironmentsOf>>]{};
  // The parts group: scenes that differ in one part, on the readings of a wall scene.
  std::vector<std::int32_t> part_counts;
  std::vector<Scene> part_scenes;
  std::vector<std::unique_ptr<TickLoop>> part_loops;
  std::size_t part_group = 0;
  LuaSpringLoops lua_spring;
  std::vector<TickLoopGroup> groups;
};

void add_environment_groups(BenchScenes& b, double seconds, BenchLoops* loops) {
  for_each_kind(b.kinds, [&](auto& environments) {
    using Environment = typename std::remove_cvref_t<decltype(environments)>::value_type::element_type;
    constexpr int N = std::remove_cvref_t<decltype(Environment::scene)>::kAxes;
    loops->first_group[N - 1] = loops->groups.size();
    for (auto& environment : environments) {
      build_rows(seconds, environment.get());
      TickLoopGroup group{&environment->feed.feed, {}};
      for (const BenchRow& row : environment->rows) group.loops.push_back(row.loop.get());
      loops->groups.push_back(std::move(group));
    }
  });
}

void add_part_group(const std::string& scripts_dir, double seconds, BenchLoops* loops) {
  loops->part_counts = record_sensor_counts(
      load_environment_text(R"({"effects": [{"type": "wall", "position": 0.01, "stiffness": 500,
        "solid": "above"}]})", "bench"), seconds);
  for (const auto& [label, json] : kPartScenes) {
    std::string text = json;
    for (std::size_t at = text.find("scripts/"); at != std::string::npos; at = text.find("scripts/", at + scripts_dir.size() + 1)) {
      text.replace(at, 7, scripts_dir);
    }
    loops->part_scenes.push_back(load_environment_text(text, "bench", "."));
  }
  TickLoopGroup parts{&loops->part_counts, {}};
  for (const Scene& scene : loops->part_scenes) {
    loops->part_loops.push_back(scene_tick_loop(scene));
    parts.loops.push_back(loops->part_loops.back().get());
  }
  loops->part_group = loops->groups.size();
  loops->groups.push_back(parts);
}

// The Lua spring groups, when the lab's spring is among the default scenes with its twin.
void add_lua_spring_groups(BenchScenes& b, bool defaults, double seconds, BenchLoops* loops) {
  const BenchEnvironmentsOf<1>& one_axis = axes_get<1>(b.kinds);
  const auto spring = std::find_if(one_axis.begin(), one_axis.end(),
                                   [](const auto& environment) { return environment->scene.name == "spring"; });
  if (!defaults || spring == one_axis.end() || !(*spring)->lua) return;
  const Scene& lua_scene = *(*spring)->lua;
  const std::vector<std::int32_t>& counts = (*spring)->feed.feed;
  LuaSpringLoops& l = loops->lua_spring;
  const Spring& spring_effect = std::get<Spring>((*spring)->scene.effects[0]);
  const PlanarScene empty = load_planar_environment_text(
      std::string(R"({"device": ")") + kBenchPolygonDevice + R"(", "effects": []})", "bench");
  const Vec2 middle = (empty.safety.workspace_min_m + empty.safety.workspace_max_m) * 0.5;
  l.planar = load_planar_environment_text(
      planar_lua_spring_environment("spring_lua_2d", kBenchPolygonDevice, spring_effect.stiffness_N_per_m, middle),
      "bench");
  l.planar_readings = record_planar_readings(*l.planar, seconds);
  l.indices = reading_indices(std::min(l.planar_readings.size(), counts.size()));
  l.one_axis = indexed_scene_tick_loop(lua_scene, counts);
  l.two_axes = planar_scene_tick_loop(*l.planar, l.planar_readings);
  l.group = loops->groups.size();
  loops->groups.push_back(TickLoopGroup{&l.indices, {l.one_axis.get(), l.two_axes.get()}});
  const ScriptProgram* one_axis_program = first_script_program(lua_scene);
  const ScriptProgram* two_axes_program = first_script_program(*l.planar);
  ScriptProgram one_axis_vm = *one_axis_program;
  ScriptProgram two_axes_vm = *two_axes_program;
  one_axis_vm.limits.translate_force = two_axes_vm.limits.translate_force = false;
  l.calls[0] = script_call_tick_loop(*one_axis_program, swinging_script_inputs(l.indices.size()));
  l.calls[1] = script_call_tick_loop(*two_axes_program,
                                     swinging_planar_script_inputs(l.indices.size(), middle[0], middle[1]));
  l.calls[2] = script_call_tick_loop(one_axis_vm, swinging_script_inputs(l.indices.size()));
  l.calls[3] = script_call_tick_loop(two_axes_vm,
                                     swinging_planar_script_inputs(l.indices.size(), middle[0], middle[1]));
  l.call_group = loops->groups.size();
  loops->groups.push_back(TickLoopGroup{&l.indices, {l.calls[0].get(), l.calls[1].get()}});
  loops->groups.push_back(TickLoopGroup{&l.indices, {l.calls[2].get(), l.calls[3].get()}});
}

// One row of a table whose names take `width` columns. The tail verdict is printed for rows
// that carry the tail goal (scripts); returns whether the row meets it (true for the others).
bool print_row(int width, const std::string& scene, const char* implementation, const TickCost& cost,
               bool tail_goal) {
  print_out("%-*s %-18s %8.1f %8.1f %8.1f %9.1f", width, scene.c_str(), implementation, cost.median_ns, cost.p99_ns,
            cost.p999_ns, cost.max_ns);
  if (cost.ratio >= 0.0) print_out(" %6.2fx", cost.ratio);
  else print_out(" %7s", "-");
  if (cost.instructions_per_tick >= 0.0) print_out(" %8.0f", cost.instructions_per_tick);
  else print_out(" %8s", "-");
  const double tail = cost.median_ns > 0.0 ? cost.p999_ns / cost.median_ns : 0.0;
  const bool ok = tail <= kBenchTailGoalRatio;
  print_out(" %6.2f", tail);
  if (tail_goal) print_out(" %s", ok ? "ok" : "OVER");
  print_out("\n");
  return ok || !tail_goal;
}

void print_table_header(int width) {
  print_out("%-*s %-18s %8s %8s %8s %9s %7s %8s %11s\n", width, "environment", "implementation", "median", "p99",
            "p99.9", "max", "ratio", "instr", "p99.9/med");
}

// A kind's rows, environment by environment, and their goals. `tails`: whether a row
// carried the tail goal, and whether every such row met it.
struct TableVerdicts {
  std::vector<std::string> goals;
  bool any_tail_goal{};
  bool tails_ok{true};
};

template <int N>
TableVerdicts print_kind_rows(const BenchEnvironmentsOf<N>& environments, const BenchLoops& loops,
                              const std::vector<std::vector<TickCost>>& costs, bool defaults) {
  TableVerdicts out;
  for (std::size_t i = 0; i < environments.size(); ++i) {
    const BenchEnvironmentOf<N>& e = *environments[i];
    std::vector<TickCost> row_costs = costs[loops.first_group[N - 1] + i];
    if (e.references == 0) {
      for (TickCost& cost : row_costs) cost.ratio = -1.0;
    }
    for (std::size_t r = 0; r < e.rows.size(); ++r) {
      const BenchRow& row = e.rows[r];
      out.any_tail_goal = out.any_tail_goal || row.tail_goal;
      out.tails_ok = print_row(BenchKindOf<N>::kNameWidth, e.scene.name, row.label, row_costs[r], row.tail_goal) &&
                     out.tails_ok;
    }
    add_bench_goals(e, row_costs, defaults, &out.goals);
  }
  return out;
}

std::string tail_goal_line(bool tails_ok) {
  char line[160];
  std::snprintf(line, sizeof line, "Lua rows: p99.9 <= %.0fx the median (no GC spikes): %s", kBenchTailGoalRatio,
                tails_ok ? "met" : "NOT met (see p99.9/med)");
  return line;
}

// What each part of a scene costs (the parts group).
void print_part_rows(const BenchLoops& loops, const std::vector<TickCost>& part_costs) {
  print_out("\nwhat each part of a scene costs (median ns per tick, measured with the rows above; "
            "ratio against the first row)\n\n");
  for (std::size_t i = 0; i < loops.part_scenes.size(); ++i) {
    print_out("%-52s %8.1f %6.2fx", kPartScenes[i][0], part_costs[i].median_ns, part_costs[i].ratio);
    if (loops.part_scenes[i].script_count > 0) {
      print_out("   %zu script effect(s), %.3f Lua calls per tick", loops.part_scenes[i].script_count,
                loops.part_loops[i]->script_calls_per_tick());
    }
    print_out("\n");
  }
}

// The 1-D table, its goals, and the parts table.
void print_one_axis_tables(const BenchScenes& b, const BenchLoops& loops, const std::vector<std::vector<TickCost>>& costs,
                           bool defaults) {
  print_table_header(BenchKindOf<1>::kNameWidth);
  const TableVerdicts verdicts = print_kind_rows(axes_get<1>(b.kinds), loops, costs, defaults);
  print_out("\ngoals\n");
  for (const std::string& goal : verdicts.goals) print_out("  %s\n", goal.c_str());
  print_out("  %s\n", tail_goal_line(verdicts.tails_ok).c_str());
  const std::vector<TickCost>& part_costs = costs[loops.part_group];
  const double fields_ratio = part_costs[kTexture10Part].median_ns > 0.0
                                  ? part_costs[kTextureFinestPart].median_ns / part_costs[kTexture10Part].median_ns
                                  : 0.0;
  print_out("  texture: 50000 fields %.2fx the cost of 10 fields (goal <= %.1fx): %s\n", fields_ratio,
            kTextureFieldsGoalRatio, fields_ratio <= kTextureFieldsGoalRatio ? "met" : "NOT met");
  print_part_rows(loops, part_costs);
}

// The 2-D table after the 1-D ones, with the Lua springs' rows and their goal.
void print_planar_table(const BenchScenes& b, const BenchLoops& loops, const std::vector<std::vector<TickCost>>& costs,
                        bool defaults) {
  constexpr int kWidth = BenchKindOf<2>::kNameWidth;
  print_out("\n2-DOF (planar): the same measure, each scene's readings from a simulated run with the hand "
            "sweeping its workspace; ratios against the hand-written 2-D code, same rounds\n\n");
  print_table_header(kWidth);
  TableVerdicts verdicts = print_kind_rows(axes_get<2>(b.kinds), loops, costs, defaults);
  const LuaSpringLoops& l = loops.lua_spring;
  if (l.two_axes) {
    TickCost one_axis = costs[l.group][0];
    one_axis.ratio = 1.0;
    print_row(kWidth, "spring (1-D)", "Lua script", one_axis, false);
    print_row(kWidth, l.planar->name, "Lua script", costs[l.group][1], false);
    for (std::size_t group : {l.call_group, l.call_group + 1}) {
      const char* label = group == l.call_group ? "force call" : "force call, VM only";
      print_row(kWidth, "spring (1-D)", label, costs[group][0], false);
      print_row(kWidth, l.planar->name, label, costs[group][1], false);
    }
    const TickCost& call_two_axes = costs[l.call_group][1];
    const double per_value = call_two_axes.ratio / 2.0;  // two values returned against one
    char goal[400];
    std::snprintf(goal, sizeof goal,
                  "%s: its force call %.2fx the 1-D Lua spring's per returned value (goal <= %.1fx): %s (the call "
                  "%.2fx for two values; whole ticks %.2fx: the 2-D tick also runs the linkage's kinematics)",
                  l.planar->name.c_str(), per_value, kLuaPlanarPerValueGoalRatio,
                  per_value <= kLuaPlanarPerValueGoalRatio ? "met" : "NOT met", call_two_axes.ratio,
                  costs[l.group][1].ratio);
    verdicts.goals.push_back(goal);
  }
  if (verdicts.any_tail_goal) verdicts.goals.push_back(tail_goal_line(verdicts.tails_ok));
  print_out("\n2-DOF goals\n");
  for (const std::string& line : verdicts.goals) print_out("  %s\n", line.c_str());
}

// A script that faulted was disabled and its row timed the 0 N left behind: the numbers
// printed are not the script's cost. Each message once on stderr; false when any faulted.
bool report_script_faults(const BenchScenes& b, const BenchLoops& loops) {
  ScriptFaultLog faults;
  const auto collect = [&](const TickLoop* loop, const std::string& where) {
    if (loop == nullptr || loop->scripts() == nullptr) return;
    for (const auto& script : *loop->scripts()) {
      if (script->disabled()) faults.add(std::string(script->fault_message()) + " (while timing " + where + ")", "");
    }
  };
  for_each_kind(b.kinds, [&](const auto& environments) {
    for (const auto& environment : environments) {
      for (const BenchRow& row : environment->rows) collect(row.loop.get(), environment->scene.name + ", " + row.label);
    }
  });
  for (std::size_t i = 0; i < loops.part_loops.size(); ++i) {
    collect(loops.part_loops[i].get(), std::string("the part \"") + kPartScenes[i][0] + "\"");
  }
  collect(loops.lua_spring.one_axis.get(), "spring (1-D), Lua script");
  collect(loops.lua_spring.two_axes.get(), "spring_lua_2d, Lua script");
  for (const auto& loop : loops.lua_spring.calls) collect(loop.get(), "the Lua springs' force calls");
  flush_out();
  for (const std::string& line : faults.report_lines()) std::fprintf(stderr, "%s\n", line.c_str());
  if (!faults.empty()) {
    std::fprintf(stderr, "hapscene bench: a script faulted and was disabled; its rows timed 0 N, not the script\n");
  }
  return faults.empty();
}

}  // namespace

int bench_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene bench");
  if (arguments.take_flag("accuracy")) return bench_accuracy(arguments);
  if (arguments.take_flag("stress")) return bench_stress(arguments);
  if (arguments.take_flag("soak")) return bench_soak(arguments);
  if (arguments.take_flag("callgrind")) return bench_callgrind(arguments);
  if (arguments.take_flag("realtime")) return bench_realtime(arguments);
  const double seconds = arguments.take(option::bench_seconds).value_or(20.0);
  const int passes = static_cast<int>(arguments.take(option::bench_passes).value_or(10));
  const std::string scripts_dir = arguments.take_value("scripts").value_or("scripts");
  std::vector<std::string> files = arguments.positionals();
  const bool defaults = files.empty();
  if (defaults) {
    files.assign(std::begin(BenchKindOf<1>::kDefaultFiles), std::end(BenchKindOf<1>::kDefaultFiles));
    files.insert(files.end(), std::begin(BenchKindOf<2>::kDefaultFiles), std::end(BenchKindOf<2>::kDefaultFiles));
  }

  BenchScenes b;
  load_bench_scenes(files, defaults, scripts_dir, &b);
  check_bench_memory(arguments, b, defaults, seconds, passes);

  TickTimer timer;
  InstructionCounter counter;
  print_preamble(seconds, passes, counter);
  // The groups: each environment's, kind by kind, the parts, the Lua springs; the rows
  // below find their costs where BenchLoops says.
  BenchLoops loops;
  add_environment_groups(b, seconds, &loops);
  add_part_group(scripts_dir, seconds, &loops);
  add_lua_spring_groups(b, defaults, seconds, &loops);

  // Everything measured in one interleaved run, then printed.
  const std::vector<std::vector<TickCost>> costs = compare_tick_loops(loops.groups, passes, &timer, &counter);
  print_one_axis_tables(b, loops, costs, defaults);
  if (!axes_get<2>(b.kinds).empty()) print_planar_table(b, loops, costs, defaults);
  return report_script_faults(b, loops) ? kExitOk : kExitFailure;
}

}  // namespace hapscene
