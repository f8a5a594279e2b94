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
#include <variant>
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

// What a callgrind run differs in per device kind (overloads on the scene type): the
// readings it replays (1 s of the closed loop), the Lua twin of --impl lua, and the
// hand-written code of --impl baseline (the 1-D lab sketch; the 2-D course code).
std::vector<std::int32_t> recorded_readings(const SceneOf<1>& scene) { return record_sensor_counts(scene, 1.0); }
std::vector<PlanarReading> recorded_readings(const SceneOf<2>& scene) { return record_planar_readings(scene, 1.0); }

std::optional<SceneOf<1>> lua_twin(Arguments& arguments, const std::string& file, const SceneOf<1>& scene,
                                   const std::string& scripts_dir) {
  std::optional<Scene> lua = lua_equivalent(scene, scripts_dir);
  if (!lua) arguments.fail(file + ": not a single lab effect");
  return lua;
}
std::optional<SceneOf<2>> lua_twin(Arguments& arguments, const std::string& file, const SceneOf<2>& scene,
                                   const std::string& /*scripts_dir*/) {
  std::optional<PlanarScene> lua = planar_lua_equivalent(scene);
  if (!lua) arguments.fail(file + ": --impl lua: a 2-DOF environment needs to be one spring (its Lua twin is timed)");
  return lua;
}

// The baseline's ticks over the readings; returns the sum of the duties it commanded.
double baseline_ticks(Arguments& arguments, const std::string& file, const SceneOf<1>& scene,
                      const std::vector<std::int32_t>& counts, long long ticks) {
  LabBaselineKind kind{};
  LabBaselineConstants constants;
  if (!lab_baseline_for(scene, &kind, &constants)) arguments.fail(file + ": not a single lab effect");
  LabBaselineState state;
  void (*tick)(const LabBaselineConstants&, std::int32_t, LabBaselineState*) =
      kind == LabBaselineKind::spring ? lab_spring_tick
      : kind == LabBaselineKind::wall ? lab_wall_tick
      : kind == LabBaselineKind::damper ? lab_damper_tick : lab_texture_tick;
  const auto n = static_cast<long long>(counts.size());
  double checksum = 0.0;
  for (long long i = 0; i < ticks; ++i) {
    tick(constants, counts[static_cast<std::size_t>(i % n)], &state);
    checksum += state.duty;
  }
  return checksum;
}
double baseline_ticks(Arguments& arguments, const std::string& file, const SceneOf<2>& scene,
                      const std::vector<PlanarReading>& readings, long long ticks) {
  PlanarBaselineKind kind{};
  PlanarBaselineConstants constants;
  if (!planar_baseline_for(scene, &kind, &constants)) {
    arguments.fail(file + ": the hand-written 2-D code is one inside box on the haplink or a 2DIY");
  }
  PlanarBaselineState state;
  void (*tick)(const PlanarBaselineConstants&, const PlanarReading&, PlanarBaselineState*) =
      kind == PlanarBaselineKind::haplink_box ? haplink_box_tick : five_bar_box_tick;
  const auto n = static_cast<long long>(readings.size());
  double checksum = 0.0;
  for (long long i = 0; i < ticks; ++i) {
    tick(constants, readings[static_cast<std::size_t>(i % n)], &state);
    checksum += state.duty[0] + state.duty[1];
  }
  return checksum;
}

// --ticks ticks of one implementation on an environment of N axes.
template <int N>
int callgrind_of(Arguments& arguments, const std::string& file, const EnvironmentOf<N>& loaded, const std::string& impl,
                 long long ticks, const std::string& scripts_dir) {
  std::optional<SceneOf<N>> lua;
  if (impl == "lua") lua = lua_twin(arguments, file, loaded.scene, scripts_dir);
  const SceneOf<N>& scene = lua ? *lua : loaded.scene;
  // The same inputs for every implementation: the environment's own closed loop.
  const auto readings = recorded_readings(loaded.scene);
  const auto n = static_cast<long long>(readings.size());
  if (n == 0) arguments.fail(file + ": no readings recorded");
  double checksum = 0.0;
  ScriptList scripts;
  if (impl == "baseline") {
    checksum = baseline_ticks(arguments, file, scene, readings, ticks);
  } else {
    TickStateOf<N> state = make_tick_state(scene);
    for (long long i = 0; i < ticks; ++i) {
      step(scene, readings[static_cast<std::size_t>(i % n)], &state);
      // The motors' duties, summed from the first (one motor: its duty, no added 0).
      double duties = motor_of(state.command, 0).duty;
      for (int k = 1; k < N; ++k) duties += motor_of(state.command, k).duty;
      checksum += duties;
    }
    scripts = std::move(state.scripts);
  }
  return report_callgrind_run(loaded.scene.name, impl, ticks, checksum, scripts);
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

  const AnyEnvironment environment = load_any_environment(files[0]);
  return std::visit([&](const auto& e) { return callgrind_of(arguments, files[0], e, impl, ticks, scripts_dir); },
                    environment);
}

}  // namespace hapscene
