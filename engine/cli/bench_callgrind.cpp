// `hapscene bench --callgrind ENV [--impl builtin|lua|baseline] [--ticks N]`: runs N ticks
// of one implementation over recorded sensor readings, untimed, so that
//   valgrind --tool=callgrind hapscene bench --callgrind ...
// counts instructions where the CPU's counters are not available. Instructions per tick
// are the difference of two tick counts divided by the difference of the counts (the
// set-up cancels): tests/bench/callgrind_per_tick.sh does that for every lab environment.
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/bench/lab_baseline.hpp"
#include "engine/bench/lua_equivalent.hpp"
#include "engine/bench/planar_tick_bench.hpp"
#include "engine/bench/tick_bench.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// The run's last line, then each script a fault disabled (it ran 0 N: the profile is not
// the script's), which makes the exit status 1.
int report_callgrind_run(const std::string& scene, const std::string& impl, long long ticks, double checksum,
                         const ScriptList& scripts) {
  print_out("callgrind mode: %s, %s, %lld ticks, checksum %.17g\n", scene.c_str(), impl.c_str(), ticks, checksum);
  flush_out();
  bool faulted = false;
  for (const auto& script : scripts) {
    if (!script->disabled()) continue;
    std::fprintf(stderr, "%s (script disabled: the ticks ran 0 N)\n", std::string(script->fault_message()).c_str());
    faulted = true;
  }
  return faulted ? 1 : 0;
}

// A 2-DOF environment: the hand-written 2-D code or step<2>() over 1 s of readings.
int planar_callgrind(Arguments& arguments, const std::string& file, const std::string& impl, long long ticks) {
  const PlanarScene loaded = load_planar_environment_file(file);
  std::optional<PlanarScene> lua;
  if (impl == "lua") {
    lua = planar_lua_equivalent(loaded);
    if (!lua) arguments.fail(file + ": --impl lua: a 2-DOF environment needs to be one spring (its Lua twin is timed)");
  }
  const PlanarScene& scene = lua ? *lua : loaded;
  // The same inputs for every implementation: 1 s of readings of the closed loop.
  const std::vector<PlanarReading> readings = record_planar_readings(loaded, 1.0);
  const auto n = static_cast<long long>(readings.size());
  if (n == 0) arguments.fail(file + ": no readings recorded");
  double checksum = 0.0;
  ScriptList scripts;
  if (impl == "baseline") {
    PlanarBaselineKind kind{};
    PlanarBaselineConstants constants;
    if (!planar_baseline_for(scene, &kind, &constants)) {
      arguments.fail(file + ": the hand-written 2-D code is one inside box on the haplink or a 2DIY");
    }
    PlanarBaselineState state;
    void (*tick)(const PlanarBaselineConstants&, const PlanarReading&, PlanarBaselineState*) =
        kind == PlanarBaselineKind::haplink_box ? haplink_box_tick : five_bar_box_tick;
    for (long long i = 0; i < ticks; ++i) {
      tick(constants, readings[static_cast<std::size_t>(i % n)], &state);
      checksum += state.duty[0] + state.duty[1];
    }
  } else {
    TickStateOf<2> state = make_tick_state(scene);
    for (long long i = 0; i < ticks; ++i) {
      step(scene, readings[static_cast<std::size_t>(i % n)], &state);
      checksum += state.command.motor[0].duty + state.command.motor[1].duty;
    }
    scripts = std::move(state.scripts);
  }
  return report_callgrind_run(loaded.name, impl, ticks, checksum, scripts);
}

}  // namespace

int bench_callgrind(Arguments& arguments) {
  const std::string impl = arguments.take_value("impl").value_or("builtin");
  const auto ticks = static_cast<long long>(arguments.take(option::callgrind_ticks).value_or(100'000));
  const std::string scripts_dir = arguments.take_value("scripts").value_or("scripts");
  const std::vector<std::string> files = arguments.positionals();
  if (files.size() != 1) arguments.fail("--callgrind: give exactly one environment file");
  if (impl != "builtin" && impl != "lua" && impl != "baseline") {
    arguments.fail("--impl: \"" + impl + "\" is not one of \"builtin\", \"lua\", \"baseline\"");
  }

  if (environment_axes(files[0]) == 2) return planar_callgrind(arguments, files[0], impl, ticks);

  // The same inputs for every implementation: 1 s of readings of the closed loop.
  const Scene scene = load_environment_file(files[0]);
  const std::vector<std::int32_t> counts = record_sensor_counts(scene, 1.0);
  const auto n = static_cast<long long>(counts.size());
  double checksum = 0.0;
  ScriptList scripts;
  if (impl == "baseline") {
    LabBaselineKind kind{};
    LabBaselineConstants constants;
    if (!lab_baseline_for(scene, &kind, &constants)) arguments.fail(files[0] + ": not a single lab effect");
    LabBaselineState state;
    void (*tick)(const LabBaselineConstants&, std::int32_t, LabBaselineState*) =
        kind == LabBaselineKind::spring ? lab_spring_tick
        : kind == LabBaselineKind::wall ? lab_wall_tick
        : kind == LabBaselineKind::damper ? lab_damper_tick : lab_texture_tick;
    for (long long i = 0; i < ticks; ++i) {
      tick(constants, counts[static_cast<std::size_t>(i % n)], &state);
      checksum += state.duty;
    }
  } else {
    std::optional<Scene> lua;
    if (impl == "lua") {
      lua = lua_equivalent(scene, scripts_dir);
      if (!lua) arguments.fail(files[0] + ": not a single lab effect");
    }
    const Scene& run = lua ? *lua : scene;
    TickState state = make_tick_state(run);
    for (long long i = 0; i < ticks; ++i) {
      step(run, counts[static_cast<std::size_t>(i % n)], &state);
      checksum += state.command.duty;
    }
    scripts = std::move(state.scripts);
  }
  return report_callgrind_run(scene.name, impl, ticks, checksum, scripts);
}

}  // namespace hapscene
