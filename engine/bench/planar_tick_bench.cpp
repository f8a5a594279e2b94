#include "engine/bench/planar_tick_bench.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "engine/bench/tick_loop_of.hpp"
#include "engine/devices/planar/planar_hand.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// The engine: step<2>() on the index-th recorded reading, with the loop's own state.
struct PlanarSceneTick {
  const PlanarScene* scene;
  const PlanarReading* readings;
  TickStateOf<2> state;
  void operator()(std::int32_t index) { step(*scene, readings[index], &state); }
};

class PlanarSceneTickLoop final : public TickLoopOf<PlanarSceneTick> {
 public:
  PlanarSceneTickLoop(const PlanarScene& scene, const std::vector<PlanarReading>& readings)
      : TickLoopOf(PlanarSceneTick{&scene, readings.data(), make_tick_state(scene)}) {}
  double script_calls_per_tick() const override {
    const TickStateOf<2>& state = tick_.state;
    return state.tick == 0 ? 0.0 : static_cast<double>(state.script_calls) / static_cast<double>(state.tick);
  }
  const ScriptList* scripts() const override { return &tick_.state.scripts; }
};

// The engine's 1-DOF step() on the index-th recorded count.
struct IndexedSceneTick {
  const Scene* scene;
  const std::int32_t* counts;
  TickState state;
  void operator()(std::int32_t index) { step(*scene, counts[index], &state); }
};

class IndexedSceneTickLoop final : public TickLoopOf<IndexedSceneTick> {
 public:
  IndexedSceneTickLoop(const Scene& scene, const std::vector<std::int32_t>& counts)
      : TickLoopOf(IndexedSceneTick{&scene, counts.data(), make_tick_state(scene)}) {}
  double script_calls_per_tick() const override {
    const TickState& state = tick_.state;
    return state.tick == 0 ? 0.0 : static_cast<double>(state.script_calls) / static_cast<double>(state.tick);
  }
  const ScriptList* scripts() const override { return &tick_.state.scripts; }
};

// The hand-written program on the index-th recorded reading, called out of line through a
// pointer the compiler cannot see through, as step() is: link-time optimisation would
// otherwise inline it into the timing loop (a Release build then timed it 1.3x faster).
template <void (*Function)(const PlanarBaselineConstants&, const PlanarReading&, PlanarBaselineState*)>
struct PlanarBaselineTick {
  PlanarBaselineConstants constants;
  const PlanarReading* readings;
  PlanarBaselineState state;
  void operator()(std::int32_t index) {
    auto* call = Function;
    asm volatile("" : "+r"(call));
    call(constants, readings[index], &state);
  }
};

template <auto Function>
std::unique_ptr<TickLoop> planar_baseline_loop(const PlanarBaselineConstants& constants,
                                               const std::vector<PlanarReading>& readings) {
  using Tick = PlanarBaselineTick<Function>;
  return std::make_unique<TickLoopOf<Tick>>(Tick{constants, readings.data(), {}});
}

}  // namespace

std::vector<PlanarReading> record_planar_readings(const PlanarScene& scene, double duration_s) {
  // The hand of `run --hand sweep` (engine/cli/run_planar.cpp): a raster over the middle
  // 80 % of the workspace box, from the profile's home.
  PlanarSimulationConfig simulation;
  PlanarHandConfig& hand = simulation.hand;
  hand.motion = PlanarHandMotion::sweep;
  const Vec2 low = scene.safety.workspace_min_m;
  const Vec2 high = scene.safety.workspace_max_m;
  const Vec2 margin = (high - low) * 0.1;
  hand.sweep_min_m = low + margin;
  hand.sweep_max_m = high - margin;
  hand.hold_m = scene.device.home_m;
  simulation.start_q_rad = planar_joint_angles_at(scene.device, scene.device.home_m);
  SimulatedPlanar device(scene.device, simulation);

  std::vector<PlanarReading> readings;
  const auto ticks = static_cast<std::uint64_t>(duration_s * scene.rate_hz);
  readings.reserve(static_cast<std::size_t>(ticks));
  TickStateOf<2> state = make_tick_state(scene);
  for (std::uint64_t i = 0; i < ticks; ++i) {
    readings.push_back(device.read());
    step(scene, readings.back(), &state);
    device.write(state.command);
    device.advance(scene.period_s);
  }
  return readings;
}

std::vector<std::int32_t> reading_indices(std::size_t n) {
  std::vector<std::int32_t> indices(n);
  for (std::size_t i = 0; i < n; ++i) indices[i] = static_cast<std::int32_t>(i);
  return indices;
}

std::unique_ptr<TickLoop> planar_scene_tick_loop(const PlanarScene& scene,
                                                 const std::vector<PlanarReading>& readings) {
  return std::make_unique<PlanarSceneTickLoop>(scene, readings);
}

std::unique_ptr<TickLoop> indexed_scene_tick_loop(const Scene& scene, const std::vector<std::int32_t>& counts) {
  return std::make_unique<IndexedSceneTickLoop>(scene, counts);
}

std::string planar_lua_spring_environment(const std::string& name, const std::string& device,
                                          double stiffness_N_per_m, const Vec2& center_m) {
  char source[400];
  std::snprintf(source, sizeof source,
                "needs = { velocity = false, time = false }\\n"
                "local K, cx, cy = %.17g, %.17g, %.17g\\n"
                "function force(s)\\n"
                "  return -K * (s.x - cx), -K * (s.y - cy)\\n"
                "end\\n",
                stiffness_N_per_m, center_m[0], center_m[1]);
  return "{\"name\": \"" + name + "\", \"device\": \"" + device +
         "\", \"effects\": [{\"type\": \"script\", \"source\": \"" + source + "\"}]}";
}

std::optional<PlanarScene> planar_lua_equivalent(const PlanarScene& scene) {
  if (scene.effects.size() != 1) return std::nullopt;
  const auto* spring = std::get_if<PlanarSpring>(&scene.effects[0]);
  if (spring == nullptr) return std::nullopt;
  // Loaded on a shipped profile, then given the scene's device, rate and safety: only the
  // effects stage differs.
  PlanarScene lua = load_planar_environment_text(
      planar_lua_spring_environment(scene.name + " (Lua)", "haplink", spring->stiffness_N_per_m, spring->center_m),
      scene.name + ".lua.json", ".");
  lua.device = scene.device;
  lua.device_file = scene.device_file;
  lua.device_model = scene.device_model;
  lua.safety = scene.safety;
  lua.velocity = scene.velocity;
  lua.rate_hz = scene.rate_hz;
  lua.period_s = scene.period_s;
  return lua;
}

std::unique_ptr<TickLoop> planar_baseline_tick_loop(const PlanarScene& scene,
                                                    const std::vector<PlanarReading>& readings) {
  PlanarBaselineKind kind{};
  PlanarBaselineConstants constants;
  if (!planar_baseline_for(scene, &kind, &constants)) return nullptr;
  switch (kind) {
    case PlanarBaselineKind::haplink_box: return planar_baseline_loop<haplink_box_tick>(constants, readings);
    case PlanarBaselineKind::five_bar_box: return planar_baseline_loop<five_bar_box_tick>(constants, readings);
  }
  return nullptr;
}

std::string regular_polygon_environment(const PlanarScene& empty, const std::string& device, int edges) {
  const Vec2 low = empty.safety.workspace_min_m;
  const Vec2 high = empty.safety.workspace_max_m;
  const Vec2 middle = (low + high) * 0.5;
  const double radius_m = 0.2 * std::fmin(high[0] - low[0], high[1] - low[1]);
  std::string text = "{\"name\": \"polygon_" + std::to_string(edges) + "\", \"device\": \"" + device +
                     "\", \"effects\": [{\"type\": \"polygon\", \"stiffness\": 200, \"solid\": \"inside\", \"points\": [";
  char point[80];
  for (int i = 0; i < edges; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / edges;
    std::snprintf(point, sizeof point, "%s[%.17g, %.17g]", i == 0 ? "" : ", ", middle[0] + radius_m * std::cos(angle),
                  middle[1] + radius_m * std::sin(angle));
    text += point;
  }
  text += "]}]}";
  return text;
}

}  // namespace hapscene
