#include "engine/bench/tick_bench.hpp"

#include "engine/bench/lab_baseline.hpp"
#include "engine/core/step.hpp"
#include "engine/devices/simulated_hapkit.hpp"

namespace hapscene {
namespace {

// A device wrapper that remembers every reading it hands out.
class RecordingDevice final : public Device {
 public:
  RecordingDevice(Device& inner, std::vector<std::int32_t>* counts) : inner_(inner), counts_(counts) {}
  std::int32_t read_counts() noexcept override {
    const std::int32_t counts = inner_.read_counts();
    counts_->push_back(counts);
    return counts;
  }
  void write(const MotorCommand& command) noexcept override { inner_.write(command); }
  void advance(double dt_s) noexcept override { inner_.advance(dt_s); }

 private:
  Device& inner_;
  std::vector<std::int32_t>* counts_;
};

template <typename Tick>
TickCost time_passes(const std::vector<std::int32_t>& counts, int passes, TickTimer* timer,
                     InstructionCounter* counter, Tick tick) {
  const std::size_t n = counts.size();
  // One untimed pass warms caches and branch predictors.
  for (std::size_t i = 0; i < n; ++i) tick(counts[i]);
  TickCost cost = timer->time(n * static_cast<std::size_t>(passes),
                              [&](std::size_t i) { tick(counts[i % n]); });
  // Instructions: one more pass between the counter's start and stop.
  if (counter != nullptr && counter->available() && n > 0) {
    counter->start();
    for (std::size_t i = 0; i < n; ++i) tick(counts[i]);
    cost.instructions_per_tick = static_cast<double>(counter->stop()) / static_cast<double>(n);
  }
  return cost;
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
    step(scene, device.read_counts(), &state);
    device.write(state.command);
    device.advance(scene.period_s);
  }
  return counts;
}

TickCost bench_scene(const Scene& scene, const std::vector<std::int32_t>& counts, int passes,
                     TickTimer* timer, InstructionCounter* counter, double* script_calls_per_tick) {
  TickState state = make_tick_state(scene);
  const TickCost cost = time_passes(counts, passes, timer, counter,
                                    [&](std::int32_t raw) { step(scene, raw, &state); });
  if (script_calls_per_tick != nullptr) {
    *script_calls_per_tick = static_cast<double>(state.script_calls) / static_cast<double>(state.tick);
  }
  return cost;
}

bool bench_lab_baseline(const Scene& scene, const std::vector<std::int32_t>& counts, int passes,
                        TickTimer* timer, TickCost* cost, InstructionCounter* counter) {
  LabBaselineKind kind{};
  LabBaselineConstants constants;
  if (!lab_baseline_for(scene, &kind, &constants)) return false;
  LabBaselineState state;
  const auto run = [&](auto tick_function) {
    return time_passes(counts, passes, timer, counter,
                       [&](std::int32_t raw) { tick_function(constants, raw, &state); });
  };
  switch (kind) {
    case LabBaselineKind::spring: *cost = run(lab_spring_tick); break;
    case LabBaselineKind::wall: *cost = run(lab_wall_tick); break;
    case LabBaselineKind::damper: *cost = run(lab_damper_tick); break;
    case LabBaselineKind::texture: *cost = run(lab_texture_tick); break;
  }
  return true;
}

}  // namespace hapscene
