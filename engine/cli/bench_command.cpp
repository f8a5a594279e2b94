// `hapscene bench [ENV...]`: per-tick compute cost of each environment next to the
// hand-written Hapkit lab baseline, and a table of what each part of a scene costs, all
// measured in one run so the ratios compare like with like.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/bench/build_info.hpp"
#include "engine/bench/instruction_counter.hpp"
#include "engine/bench/lua_equivalent.hpp"
#include "engine/bench/planar_tick_bench.hpp"
#include "engine/bench/script_call_bench.hpp"
#include "engine/bench/tick_bench.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

constexpr const char* kLabEnvironments[] = {"environments/spring.json", "environments/wall.json",
                                            "environments/damper.json", "environments/texture.json"};

// The 2-D rows by default: the course's inside box on both devices (against the
// hand-written 2-D code), a round cage, and a polygon of kPolygonEdges edges.
constexpr const char* kPlanarEnvironments[] = {"environments/planar/haplink_box_inside.json",
                                               "environments/planar/haply2diy_v3_box_inside.json",
                                               "environments/planar/haplink_circle_outside.json"};
constexpr int kPolygonEdges = 1000;
constexpr const char* kPolygonDevice = "haplink";

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

// Built-in 1-D effects against the lab's sketch called out of line (the like-for-like row:
// the engine's step() is called out of line too); the hand-folded floor is printed as the
// ratios' reference, without a verdict (it has no safety stage and a simpler flip counter).
constexpr double kBuiltinSketchGoalRatio = 1.0;
// Built-in 2-D boxes against the hand-written course code.
constexpr double kPlanarBoxGoalRatio = 1.5;
constexpr double kLuaGoal_ns = 150.0;         // Lua scripts, median per tick
constexpr double kLuaSpringGoal_ns = 50.0;    // scripts/spring.lua, median per tick (at most)
constexpr double kLuaTextureGoal_ns = 70.0;   // scripts/texture.lua, median per tick (under)
constexpr double kTextureFieldsGoalRatio = 1.1;  // texture at 50 000 fields (the finest) against 10 fields
// The parts rows the texture goal compares (indices into kPartScenes).
constexpr std::size_t kTexture10Part = 5;
constexpr std::size_t kTextureFinestPart = 7;
constexpr double kTailGoalRatio = 5.0;        // Lua scripts: p99.9 against the median (no GC spikes)
constexpr double kPolygonGoal_ns = 1000.0;    // the 1000-edge polygon, median per tick
// The 2-D Lua spring's force call against the 1-D one's, per returned value (it returns
// two); the whole ticks' ratio is printed without a verdict (the 2-D tick also runs the
// linkage's kinematics).
constexpr double kLuaPlanarPerValueGoalRatio = 1.0;

void print_header() {
  print_out("%-10s %-18s %8s %8s %8s %9s %7s %8s %11s\n", "environment", "implementation", "median", "p99",
            "p99.9", "max", "ratio", "instr", "p99.9/med");
}

// One row. The tail verdict is printed for rows that carry the tail goal (Lua scripts);
// returns whether the row meets it (true for the others).
bool print_row(const std::string& scene, const char* implementation, const TickCost& cost, bool tail_goal) {
  print_out("%-10s %-18s %8.1f %8.1f %8.1f %9.1f", scene.c_str(), implementation, cost.median_ns, cost.p99_ns,
            cost.p999_ns, cost.max_ns);
  if (cost.ratio >= 0.0) print_out(" %6.2fx", cost.ratio);
  else print_out(" %7s", "-");
  if (cost.instructions_per_tick >= 0.0) print_out(" %8.0f", cost.instructions_per_tick);
  else print_out(" %8s", "-");
  const double tail = cost.median_ns > 0.0 ? cost.p999_ns / cost.median_ns : 0.0;
  const bool ok = tail <= kTailGoalRatio;
  print_out(" %6.2f %s\n", tail, !tail_goal ? "" : ok ? "ok" : "OVER");
  return ok || !tail_goal;
}

// The 2-D table and its goals, after the 1-D ones: each scene's hand-written 2-D code
// (when there is one for it) and step<2>() on its recorded readings.
struct PlanarRow {
  const PlanarScene* scene;
  std::vector<TickCost> costs;  // the baseline's first when there is one
  bool has_baseline;
  bool polygon_goal;            // the generated kPolygonEdges-edge polygon
};

void print_planar_row(const std::string& scene, const char* implementation, const TickCost& cost) {
  print_out("%-24s %-18s %8.1f %8.1f %8.1f %9.1f", scene.c_str(), implementation, cost.median_ns, cost.p99_ns,
            cost.p999_ns, cost.max_ns);
  if (cost.ratio >= 0.0) print_out(" %6.2fx", cost.ratio);
  else print_out(" %7s", "-");
  if (cost.instructions_per_tick >= 0.0) print_out(" %8.0f", cost.instructions_per_tick);
  else print_out(" %8s", "-");
  print_out(" %6.2f\n", cost.median_ns > 0.0 ? cost.p999_ns / cost.median_ns : 0.0);
}

// The Lua spring in 1-D and in 2-D, timed in one group (the 2-D one's ratio is against
// the 1-D one, round by round).
struct LuaSpringRows {
  std::string planar_name;
  TickCost one_axis;
  TickCost two_axes;
  TickCost call_one_axis, call_two_axes;        // force(s) alone, as it runs (translated)
  TickCost vm_call_one_axis, vm_call_two_axes;  // force(s) alone, in the VM alone
};

void print_planar_table(const std::vector<PlanarRow>& rows, const LuaSpringRows* lua) {
  print_out("\n2-DOF (planar): the same measure, each scene's readings from a simulated run with the hand "
            "sweeping its workspace; ratios against the hand-written 2-D code, same rounds\n\n");
  print_out("%-24s %-18s %8s %8s %8s %9s %7s %8s %11s\n", "environment", "implementation", "median", "p99", "p99.9",
            "max", "ratio", "instr", "p99.9/med");
  std::vector<std::string> goals;
  char goal[320];
  for (const PlanarRow& row : rows) {
    const std::string& name = row.scene->name;
    std::size_t k = 0;
    if (row.has_baseline) print_planar_row(name, "hand-written C++", row.costs[k++]);
    TickCost builtin = row.costs[k];
    if (!row.has_baseline) builtin.ratio = -1.0;
    print_planar_row(name, "built-in (JSON)", builtin);
    if (row.has_baseline) {
      std::snprintf(goal, sizeof goal, "%s: built-in %.2fx the hand-written code (goal <= %.1fx): %s", name.c_str(),
                    builtin.ratio, kPlanarBoxGoalRatio, builtin.ratio <= kPlanarBoxGoalRatio ? "met" : "NOT met");
      goals.push_back(goal);
    }
    if (row.polygon_goal) {
      std::snprintf(goal, sizeof goal, "%s: built-in median %.1f ns (goal < %.0f ns): %s", name.c_str(),
                    builtin.median_ns, kPolygonGoal_ns, builtin.median_ns < kPolygonGoal_ns ? "met" : "NOT met");
      goals.push_back(goal);
    }
  }
  if (lua != nullptr) {
    TickCost one_axis = lua->one_axis;
    one_axis.ratio = 1.0;
    print_planar_row("spring (1-D)", "Lua script", one_axis);
    print_planar_row(lua->planar_name, "Lua script", lua->two_axes);
    for (const auto& [name, cost, vm] :
         {std::tuple{"spring (1-D)", lua->call_one_axis, false}, std::tuple{lua->planar_name.c_str(), lua->call_two_axes, false},
          std::tuple{"spring (1-D)", lua->vm_call_one_axis, true},
          std::tuple{lua->planar_name.c_str(), lua->vm_call_two_axes, true}}) {
      TickCost row = cost;
      print_planar_row(name, vm ? "force call, VM only" : "force call", row);
    }
    const double per_value = lua->call_two_axes.ratio / 2.0;  // two values returned against one
    std::snprintf(goal, sizeof goal,
                  "%s: its force call %.2fx the 1-D Lua spring's per returned value (goal <= %.1fx): %s (the call "
                  "%.2fx for two values; whole ticks %.2fx: the 2-D tick also runs the linkage's kinematics)",
                  lua->planar_name.c_str(), per_value, kLuaPlanarPerValueGoalRatio,
                  per_value <= kLuaPlanarPerValueGoalRatio ? "met" : "NOT met", lua->call_two_axes.ratio,
                  lua->two_axes.ratio);
    goals.push_back(goal);
  }
  print_out("\n2-DOF goals\n");
  for (const std::string& line : goals) print_out("  %s\n", line.c_str());
}

// Whether a loop's scripts run a translated force (then a VM-only row shows the difference).
bool runs_translated(const TickLoop& loop) {
  if (loop.scripts() == nullptr) return false;
  for (const auto& script : *loop.scripts()) {
    if (script->force_translated()) return true;
  }
  return false;
}

// What a scene's engine row runs: built-in effects only, scripts only (a .lua
// environment, or JSON made of script effects), or both.
const char* implementation_label(const Scene& scene) {
  if (scene.script_count == 0) return "built-in (JSON)";
  if (scene.script_count == scene.effects.size()) return "Lua script";
  return "built-in + Lua";
}

// The memory the values drive, estimated before anything is recorded: the recorded
// readings (4 bytes a tick per environment), two timings per round for every loop
// (rounds = passes x slices of the longest recording) and one timing per tick of the
// tail measurement (readings x passes / kTailRepeats, the longest loop at a time).
// Over kMaxBenchBytes the command is refused, naming the values to lower.
constexpr double kMaxBenchBytes = 1024.0 * 1024.0 * 1024.0;  // 1 GiB

std::string mebibytes(double bytes) { return format_number(std::round(bytes / (1024.0 * 1024.0))) + " MiB"; }

void check_bench_memory(const Arguments& arguments, const std::vector<Scene>& scenes,
                        const std::vector<PlanarScene>& planar_scenes, bool defaults, double seconds, int passes) {
  double longest_ticks = std::floor(seconds * 1000.0);  // the parts group runs at the default 1 kHz
  double readings = longest_ticks;
  for (const Scene& scene : scenes) {
    const double ticks = std::floor(seconds * scene.rate_hz);
    readings += ticks;
    longest_ticks = std::max(longest_ticks, ticks);
  }
  // A 2-D reading, and its index, count as (sizeof(PlanarReading) + 4) / 4 readings.
  constexpr double kPlanarReadingWeight = (static_cast<double>(sizeof(PlanarReading)) + 4.0) / 4.0;
  for (const PlanarScene& scene : planar_scenes) {
    const double ticks = std::floor(seconds * scene.rate_hz);
    readings += kPlanarReadingWeight * ticks;
    longest_ticks = std::max(longest_ticks, ticks);
  }
  // The default rows add the Lua spring in 1-D and 2-D: a 2-D recording and two loops.
  if (defaults) readings += kPlanarReadingWeight * std::floor(seconds * 1000.0);
  const double loops = 6.0 * static_cast<double>(scenes.size()) + 2.0 * static_cast<double>(planar_scenes.size()) +
                       static_cast<double>(std::size(kPartScenes)) + (defaults ? 6.0 : 0.0);
  const double slices = std::max(1.0, std::floor(longest_ticks / static_cast<double>(kSliceTicks)));
  const double readings_bytes = 4.0 * readings;
  const double rounds_bytes = 2.0 * 8.0 * static_cast<double>(passes) * slices * loops;
  const double tail_bytes = 8.0 * longest_ticks * static_cast<double>(passes) / static_cast<double>(TickTimer::kTailRepeats);
  const double total = readings_bytes + rounds_bytes + tail_bytes;
  if (total > kMaxBenchBytes) {
    arguments.fail("--seconds " + format_number(seconds) + " x --passes " + std::to_string(passes) + " over " +
                   std::to_string(scenes.size() + planar_scenes.size()) + " environment(s) needs about " + mebibytes(total) +
                   " (readings " + mebibytes(readings_bytes) + ", round timings " + mebibytes(rounds_bytes) +
                   ", tail timings " + mebibytes(tail_bytes) + "), more than the " + mebibytes(kMaxBenchBytes) +
                   " a bench may use; lower --seconds or --passes, or give fewer environments");
  }
}

// The scenes a bench run times: the 1-D ones with their Lua twins, and the 2-DOF ones (a
// planar device's environment goes to the 2-D table). Every one is loaded before anything
// is timed.
struct BenchScenes {
  std::vector<Scene> scenes;
  std::vector<std::optional<Scene>> lua_scenes;
  std::vector<PlanarScene> planar_scenes;
};

BenchScenes load_bench_scenes(const std::vector<std::string>& files, bool defaults, const std::string& scripts_dir) {
  BenchScenes b;
  for (const std::string& file : files) {
    if (environment_axes(file) == 2) {
      b.planar_scenes.push_back(load_planar_environment_file(file));
      continue;
    }
    b.scenes.push_back(load_environment_file(file));
    b.lua_scenes.push_back(lua_equivalent(b.scenes.back(), scripts_dir));
  }
  if (defaults) {
    for (const char* file : kPlanarEnvironments) b.planar_scenes.push_back(load_planar_environment_file(file));
    const PlanarScene empty =
        load_planar_environment_text(std::string(R"({"device": ")") + kPolygonDevice + R"(", "effects": []})", "bench");
    b.planar_scenes.push_back(
        load_planar_environment_text(regular_polygon_environment(empty, kPolygonDevice, kPolygonEdges), "bench"));
  }
  return b;
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

// One 1-D environment's group: the hand-written code first (the ratios' reference), then
// the engine, then Lua, on the environment's own recorded readings.
struct EnvironmentLoops {
  std::vector<std::int32_t> counts;
  std::unique_ptr<TickLoop> baseline, sketch_inline, sketch_out_of_line, builtin, lua, lua_vm;
};

// One 2-D environment's group: the hand-written 2-D code first (when there is one), then step<2>().
struct PlanarLoops {
  std::vector<PlanarReading> readings;
  std::vector<std::int32_t> indices;
  std::unique_ptr<TickLoop> baseline, builtin;
};

// The Lua spring in 1-D (the spring row's Lua scene on its readings) and in 2-D (on the
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

  std::vector<EnvironmentLoops> environments;
  // The Lua twins with every force run by the VM alone, beside the twins as they run (a
  // straight-line numeric force is translated): what the translation saves.
  std::vector<std::optional<Scene>> lua_vm_scenes;
  // The parts group: scenes that differ in one part, on the readings of a wall scene.
  std::vector<std::int32_t> part_counts;
  std::vector<Scene> part_scenes;
  std::vector<std::unique_ptr<TickLoop>> part_loops;
  std::vector<PlanarLoops> planar;
  LuaSpringLoops lua_spring;
  std::vector<TickLoopGroup> groups;
};

void add_environment_groups(const BenchScenes& b, double seconds, BenchLoops* loops) {
  loops->environments.resize(b.scenes.size());
  loops->lua_vm_scenes.resize(b.scenes.size());
  for (std::size_t i = 0; i < b.scenes.size(); ++i) {
    EnvironmentLoops& e = loops->environments[i];
    e.counts = record_sensor_counts(b.scenes[i], seconds);
    // The reference (first) is the folded floor; the sketch rows come with it.
    e.baseline = lab_folded_tick_loop(b.scenes[i]);
    if (e.baseline) {
      e.sketch_inline = lab_baseline_tick_loop(b.scenes[i]);
      e.sketch_out_of_line = lab_sketch_out_of_line_tick_loop(b.scenes[i]);
    }
    e.builtin = scene_tick_loop(b.scenes[i]);
    if (b.lua_scenes[i]) {
      e.lua = scene_tick_loop(*b.lua_scenes[i]);
      if (runs_translated(*e.lua)) {
        loops->lua_vm_scenes[i] = with_scripts_in_vm(*b.lua_scenes[i]);
        e.lua_vm = scene_tick_loop(*loops->lua_vm_scenes[i]);
      }
    }
    TickLoopGroup group{&e.counts, {}};
    for (TickLoop* loop : {e.baseline.get(), e.sketch_inline.get(), e.sketch_out_of_line.get(), e.builtin.get(),
                           e.lua.get(), e.lua_vm.get()}) {
      if (loop != nullptr) group.loops.push_back(loop);
    }
    loops->groups.push_back(std::move(group));
  }
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
  loops->groups.push_back(parts);
}

void add_planar_groups(const BenchScenes& b, double seconds, BenchLoops* loops) {
  loops->planar.resize(b.planar_scenes.size());
  for (std::size_t i = 0; i < b.planar_scenes.size(); ++i) {
    PlanarLoops& p = loops->planar[i];
    p.readings = record_planar_readings(b.planar_scenes[i], seconds);
    p.indices = reading_indices(p.readings.size());
    p.baseline = planar_baseline_tick_loop(b.planar_scenes[i], p.readings);
    p.builtin = planar_scene_tick_loop(b.planar_scenes[i], p.readings);
    TickLoopGroup group{&p.indices, {}};
    if (p.baseline) group.loops.push_back(p.baseline.get());
    group.loops.push_back(p.builtin.get());
    loops->groups.push_back(std::move(group));
  }
}

// The Lua spring groups, when the lab's spring is among the default scenes with its twin.
void add_lua_spring_groups(const BenchScenes& b, bool defaults, double seconds, BenchLoops* loops) {
  const auto spring =
      std::find_if(b.scenes.begin(), b.scenes.end(), [](const Scene& scene) { return scene.name == "spring"; });
  if (!defaults || spring == b.scenes.end() || !b.lua_scenes[static_cast<std::size_t>(spring - b.scenes.begin())]) {
    return;
  }
  const std::size_t i = static_cast<std::size_t>(spring - b.scenes.begin());
  const Scene& lua_scene = *b.lua_scenes[i];
  const std::vector<std::int32_t>& counts = loops->environments[i].counts;
  LuaSpringLoops& l = loops->lua_spring;
  const Spring& spring_effect = std::get<Spring>(spring->effects[0]);
  const PlanarScene empty =
      load_planar_environment_text(std::string(R"({"device": ")") + kPolygonDevice + R"(", "effects": []})", "bench");
  const Vec2 middle = (empty.safety.workspace_min_m + empty.safety.workspace_max_m) * 0.5;
  l.planar = load_planar_environment_text(
      planar_lua_spring_environment("spring_lua_2d", kPolygonDevice, spring_effect.stiffness_N_per_m, middle), "bench");
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

// The 1-D rows, each environment's group in turn, and their goals; false when a Lua
// row's tail goal was missed.
bool print_environment_rows(const BenchScenes& b, const BenchLoops& loops,
                            const std::vector<std::vector<TickCost>>& costs, bool defaults,
                            std::vector<std::string>* goals) {
  bool tails_ok = true;
  for (std::size_t i = 0; i < b.scenes.size(); ++i) {
    const Scene& scene = b.scenes[i];
    const EnvironmentLoops& e = loops.environments[i];
    std::vector<TickCost> row_costs = costs[i];
    if (!e.baseline) {
      for (TickCost& cost : row_costs) cost.ratio = -1.0;
    }
    std::size_t row = 0;
    if (e.baseline) {
      print_row(scene.name, "hand-folded floor", row_costs[row++], false);
      print_row(scene.name, "sketch, inlined", row_costs[row++], false);
      print_row(scene.name, "sketch, call", row_costs[row++], false);
    }
    const TickCost builtin_cost = row_costs[row++];
    // A row that runs scripts carries the Lua rows' tail goal.
    const bool has_scripts = scene.script_count > 0;
    const bool builtin_tail_ok = print_row(scene.name, implementation_label(scene), builtin_cost, has_scripts);
    tails_ok = builtin_tail_ok && tails_ok;
    char goal[240];
    if (e.baseline) {
      // The like-for-like row: the sketch called out of line (row 2), in the same rounds.
      const double sketch_call_ns = row_costs[2].median_ns;
      const bool measured = sketch_call_ns > 0.0 && builtin_cost.median_ns > 0.0;
      const double ratio = measured ? builtin_cost.median_ns / sketch_call_ns : 0.0;
      std::snprintf(goal, sizeof goal, "%s: built-in %.2fx the lab sketch called out of line (goal <= %.1fx): %s",
                    scene.name.c_str(), ratio, kBuiltinSketchGoalRatio,
                    !measured ? "not measured" : ratio <= kBuiltinSketchGoalRatio ? "met" : "NOT met");
      goals->push_back(goal);
    }
    if (e.lua) {
      const TickCost lua_cost = row_costs[row++];
      tails_ok = print_row(scene.name, "Lua script", lua_cost, true) && tails_ok;
      if (e.lua_vm) print_row(scene.name, "Lua, VM only", row_costs[row++], false);
      std::snprintf(goal, sizeof goal, "%s: Lua median %.1f ns (goal < %.0f ns): %s", scene.name.c_str(),
                    lua_cost.median_ns, kLuaGoal_ns, lua_cost.median_ns < kLuaGoal_ns ? "met" : "NOT met");
      goals->push_back(goal);
      // The shipped spring and texture scripts have goals of their own.
      if (defaults && (scene.name == "spring" || scene.name == "texture")) {
        const bool spring_row = scene.name == "spring";
        const double limit_ns = spring_row ? kLuaSpringGoal_ns : kLuaTextureGoal_ns;
        const bool met = spring_row ? lua_cost.median_ns <= limit_ns : lua_cost.median_ns < limit_ns;
        std::snprintf(goal, sizeof goal, "%s: Lua median %.1f ns (goal %s %.0f ns): %s", scene.name.c_str(),
                      lua_cost.median_ns, spring_row ? "<=" : "<", limit_ns, met ? "met" : "NOT met");
        goals->push_back(goal);
      }
    }
  }
  return tails_ok;
}

// What each part of a scene costs (the parts group, after the environments' groups).
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
  for (std::size_t i = 0; i < b.scenes.size(); ++i) {
    collect(loops.environments[i].builtin.get(), b.scenes[i].name + ", " + implementation_label(b.scenes[i]));
    collect(loops.environments[i].lua.get(), b.scenes[i].name + ", Lua script");
  }
  for (std::size_t i = 0; i < loops.part_loops.size(); ++i) {
    collect(loops.part_loops[i].get(), std::string("the part \"") + kPartScenes[i][0] + "\"");
  }
  collect(loops.lua_spring.one_axis.get(), "spring (1-D), Lua script");
  collect(loops.lua_spring.two_axes.get(), "spring_lua_2d, Lua script");
  for (const auto& loop : loops.lua_spring.calls) collect(loop.get(), "the Lua springs' force calls");
  for (std::size_t i = 0; i < b.scenes.size(); ++i) {
    collect(loops.environments[i].lua_vm.get(), b.scenes[i].name + ", Lua, VM only");
  }
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
  if (defaults) files.assign(std::begin(kLabEnvironments), std::end(kLabEnvironments));

  const BenchScenes b = load_bench_scenes(files, defaults, scripts_dir);
  check_bench_memory(arguments, b.scenes, b.planar_scenes, defaults, seconds, passes);

  TickTimer timer;
  InstructionCounter counter;
  print_preamble(seconds, passes, counter);
  // The groups in this order: each 1-D environment, the parts, each 2-D environment, the
  // Lua springs; the rows below read the costs back in the same order.
  BenchLoops loops;
  add_environment_groups(b, seconds, &loops);
  add_part_group(scripts_dir, seconds, &loops);
  add_planar_groups(b, seconds, &loops);
  add_lua_spring_groups(b, defaults, seconds, &loops);

  // Everything measured in one interleaved run, then printed.
  const std::vector<std::vector<TickCost>> costs = compare_tick_loops(loops.groups, passes, &timer, &counter);

  print_header();
  std::vector<std::string> goals;
  const bool tails_ok = print_environment_rows(b, loops, costs, defaults, &goals);
  print_out("\ngoals\n");
  for (const std::string& goal : goals) print_out("  %s\n", goal.c_str());
  print_out("  Lua rows: p99.9 <= %.0fx the median (no GC spikes): %s\n", kTailGoalRatio,
            tails_ok ? "met" : "NOT met (see p99.9/med)");

  const std::vector<TickCost>& part_costs = costs[b.scenes.size()];
  const double fields_ratio = part_costs[kTexture10Part].median_ns > 0.0
                                  ? part_costs[kTextureFinestPart].median_ns / part_costs[kTexture10Part].median_ns
                                  : 0.0;
  print_out("  texture: 50000 fields %.2fx the cost of 10 fields (goal <= %.1fx): %s\n", fields_ratio,
            kTextureFieldsGoalRatio, fields_ratio <= kTextureFieldsGoalRatio ? "met" : "NOT met");
  print_part_rows(loops, part_costs);

  if (!b.planar_scenes.empty()) {
    std::vector<PlanarRow> rows;
    for (std::size_t i = 0; i < b.planar_scenes.size(); ++i) {
      rows.push_back(PlanarRow{&b.planar_scenes[i], costs[b.scenes.size() + 1 + i], loops.planar[i].baseline != nullptr,
                               defaults && i + 1 == b.planar_scenes.size()});
    }
    std::optional<LuaSpringRows> lua;
    const LuaSpringLoops& l = loops.lua_spring;
    if (l.two_axes) {
      lua = LuaSpringRows{l.planar->name, costs[l.group][0], costs[l.group][1], costs[l.call_group][0],
                          costs[l.call_group][1], costs[l.call_group + 1][0], costs[l.call_group + 1][1]};
    }
    print_planar_table(rows, lua ? &*lua : nullptr);
  }
  return report_script_faults(b, loops) ? kExitOk : kExitFailure;
}

}  // namespace hapscene
