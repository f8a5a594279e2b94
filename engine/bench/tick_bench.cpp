#include "engine/bench/tick_bench.hpp"

#include <algorithm>
#include <chrono>

#include "engine/bench/lab_baseline.hpp"
#include "engine/bench/tick_loop_of.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// A device wrapper that remembers every reading it hands out.
class RecordingDevice final : public Device {
 public:
  RecordingDevice(Device& inner, std::vector<std::int32_t>* counts) : inner_(inner), counts_(counts) {}
  std::int32_t read() noexcept override {
    const std::int32_t counts = inner_.read();
    counts_->push_back(counts);
    return counts;
  }
  void write(const MotorCommand& command) noexcept override { inner_.write(command); }
  void advance(double dt_s) noexcept override { inner_.advance(dt_s); }

 private:
  Device& inner_;
  std::vector<std::int32_t>* counts_;
};

// The engine: step() with the loop's own state.
struct SceneTick {
  const Scene* scene;
  TickState state;
  void operator()(std::int32_t raw) { step(*scene, raw, &state); }
};

class SceneTickLoop final : public TickLoopOf<SceneTick> {
 public:
  explicit SceneTickLoop(const Scene& scene) : TickLoopOf(SceneTick{&scene, make_tick_state(scene)}) {}
  double script_calls_per_tick() const override {
    const TickState& state = tick_.state;
    return state.tick == 0 ? 0.0 : static_cast<double>(state.script_calls) / static_cast<double>(state.tick);
  }
  const ScriptList* scripts() const override { return &tick_.state.scripts; }
};

// The hand-written sketch for one lab effect (a direct call, as step() is).
template <void (*Function)(const LabBaselineConstants&, std::int32_t, LabBaselineState*)>
struct BaselineTick {
  LabBaselineConstants constants;
  LabBaselineState state;
  void operator()(std::int32_t raw) { Function(constants, raw, &state); }
};

template <auto Function>
std::unique_ptr<TickLoop> baseline_loop(const LabBaselineConstants& constants) {
  return std::make_unique<TickLoopOf<BaselineTick<Function>>>(BaselineTick<Function>{constants, {}});
}

// The same through a function pointer the compiler cannot see through, so it is called
// out of line (one call per tick, as step() is) even when link-time optimisation could
// inline it into the timing loop.
template <typename Constants>
struct OutOfLineTick {
  void (*function)(const Constants&, std::int32_t, LabBaselineState*) noexcept;
  Constants constants;
  LabBaselineState state;
  void operator()(std::int32_t raw) {
    auto* call = function;
    asm volatile("" : "+r"(call));
    call(constants, raw, &state);
  }
};

template <typename Constants>
std::unique_ptr<TickLoop> out_of_line_loop(void (*function)(const Constants&, std::int32_t, LabBaselineState*) noexcept,
                                           const Constants& constants) {
  return std::make_unique<TickLoopOf<OutOfLineTick<Constants>>>(OutOfLineTick<Constants>{function, constants, {}});
}

constexpr std::chrono::milliseconds kWarmUp{300};

double median_of(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

std::vector<std::int32_t> record_sensor_counts(const Scene& scene, double duration_s) {
  SimulatedHapkit sim(scene.device, SimulationConfig{});
  std::vector<std::int32_t> counts;
  counts.reserve(static_cast<std::size_t>(duration_s * scene.rate_hz) + 1);
  RecordingDevice device(sim, &counts);
  TickState state = make_tick_state(scene);
  const auto ticks = static_cast<std::uint64_t>(duration_s * scene.rate_hz);
  for (std::uint64_t i = 0; i < ticks; ++i) {
    step(scene, device.read(), &state);
    device.write(state.command);
    device.advance(scene.period_s);
  }
  return counts;
}

std::unique_ptr<TickLoop> scene_tick_loop(const Scene& scene) {
  return std::make_unique<SceneTickLoop>(scene);
}

std::unique_ptr<TickLoop> lab_baseline_tick_loop(const Scene& scene) {
  LabBaselineKind kind{};
  LabBaselineConstants constants;
  if (!lab_baseline_for(scene, &kind, &constants)) return nullptr;
  switch (kind) {
    case LabBaselineKind::spring: return baseline_loop<lab_spring_tick>(constants);
    case LabBaselineKind::wall: return baseline_loop<lab_wall_tick>(constants);
    case LabBaselineKind::damper: return baseline_loop<lab_damper_tick>(constants);
    case LabBaselineKind::texture: return baseline_loop<lab_texture_tick>(constants);
  }
  return nullptr;
}

std::unique_ptr<TickLoop> lab_sketch_out_of_line_tick_loop(const Scene& scene) {
  LabBaselineKind kind{};
  LabBaselineConstants constants;
  if (!lab_baseline_for(scene, &kind, &constants)) return nullptr;
  switch (kind) {
    case LabBaselineKind::spring: return out_of_line_loop(&lab_spring_tick, constants);
    case LabBaselineKind::wall: return out_of_line_loop(&lab_wall_tick, constants);
    case LabBaselineKind::damper: return out_of_line_loop(&lab_damper_tick, constants);
    case LabBaselineKind::texture: return out_of_line_loop(&lab_texture_tick, constants);
  }
  return nullptr;
}

std::unique_ptr<TickLoop> lab_folded_tick_loop(const Scene& scene) {
  LabBaselineKind kind{};
  LabBaselineConstants constants;
  if (!lab_baseline_for(scene, &kind, &constants)) return nullptr;
  const LabFoldedConstants folded = fold_lab_constants(constants);
  switch (kind) {
    case LabBaselineKind::spring: return out_of_line_loop(&lab_spring_folded, folded);
    case LabBaselineKind::wall: return out_of_line_loop(&lab_wall_folded, folded);
    case LabBaselineKind::damper: return out_of_line_loop(&lab_damper_folded, folded);
    case LabBaselineKind::texture: return out_of_line_loop(&lab_texture_folded, folded);
  }
  return nullptr;
}

std::vector<std::vector<TickCost>> compare_tick_loops(const std::vector<TickLoopGroup>& groups,
                                                      int passes, TickTimer* timer,
                                                      InstructionCounter* counter) {
  // Untimed passes over every loop for at least kWarmUp warm caches and branch
  // predictors, and let a virtual CPU that was idle reach its working clock (a bench
  // started cold measured its first group up to 1.5x slow without this).
  const auto warm_until = std::chrono::steady_clock::now() + kWarmUp;
  do {
    for (const TickLoopGroup& group : groups) {
      for (TickLoop* loop : group.loops) loop->time_slice(*timer, *group.counts, 0, group.counts->size());
    }
  } while (std::chrono::steady_clock::now() < warm_until);

  // Rounds: one slice of each loop of each group, starting with a different one each round.
  std::size_t slices = 1;
  for (const TickLoopGroup& group : groups) slices = std::max(slices, group.counts->size() / kSliceTicks);
  const std::size_t rounds = static_cast<std::size_t>(passes) * slices;
  std::vector<std::vector<std::vector<double>>> round_ns(groups.size());
  std::vector<std::vector<std::vector<double>>> round_ratio(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    round_ns[g].resize(groups[g].loops.size());
    round_ratio[g].resize(groups[g].loops.size());
  }
  std::vector<double> this_round;
  for (std::size_t round = 0; round < rounds; ++round) {
    for (std::size_t h = 0; h < groups.size(); ++h) {
      const TickLoopGroup& group = groups[(round + h) % groups.size()];
      auto& group_ns = round_ns[(round + h) % groups.size()];
      auto& group_ratio = round_ratio[(round + h) % groups.size()];
      const std::size_t k = group.loops.size();
      const std::size_t group_slices = std::max<std::size_t>(1, group.counts->size() / kSliceTicks);
      const std::size_t begin = (round % group_slices) * kSliceTicks;
      const std::size_t end = std::min(group.counts->size(), begin + kSliceTicks);
      this_round.assign(k, 0.0);
      for (std::size_t j = 0; j < k; ++j) {
        const std::size_t which = (round + j) % k;
        this_round[which] = group.loops[which]->time_slice(*timer, *group.counts, begin, end);
      }
      for (std::size_t j = 0; j < k; ++j) {
        group_ns[j].push_back(this_round[j]);
        if (this_round[0] > 0.0) group_ratio[j].push_back(this_round[j] / this_round[0]);
      }
    }
  }

  std::vector<std::vector<TickCost>> costs(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::size_t j = 0; j < groups[g].loops.size(); ++j) {
      TickCost cost;
      cost.median_ns = median_of(round_ns[g][j]);
      cost.ratio = round_ratio[g][j].empty() ? -1.0 : median_of(round_ratio[g][j]);
      TickLoop* loop = groups[g].loops[j];
      loop->time_tail(*timer, *groups[g].counts, passes, &cost);
      if (counter != nullptr && counter->available()) {
        cost.instructions_per_tick = loop->instructions_per_tick(*counter, *groups[g].counts);
      }
      costs[g].push_back(cost);
    }
  }
  return costs;
}

}  // namespace hapscene
