#pragma once
// A run of one environment as `hapscene run --sim-time --log` does it (the same
// run_watched, the same tick samples), kept in memory instead of written to a CSV file,
// with the simulator's true state beside each tick. The Python module's simulate() is
// built on it (python/). The memory is reserved before the run; on_tick never allocates.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/cli/run_session.hpp"
#include "engine/cli/run_settings.hpp"
#include "engine/devices/device.hpp"
#include "engine/run/telemetry_log.hpp"

namespace hapscene {

// The simulator's state at one tick (SimulationTruthOf<N>); zeros for a device without one.
template <int N>
struct TruthSampleOf {
  Axes<N> x_m{};
  Axes<N> v_m_per_s{};
  Axes<N> motor_force_N{};
  Axes<N> hand_force_N{};
};

// Keeps every tick's telemetry sample and truth, up to the capacity it was given.
template <int N>
class RunRecorderOf final : public TickObserverOf<N> {
 public:
  RunRecorderOf(const SimulationTruthOf<N>* truth, std::size_t capacity) : truth_(truth) {
    samples_.reserve(capacity);
    truths_.reserve(capacity);
  }

  void on_tick(const TickStateOf<N>& state) noexcept override {
    if (samples_.size() == samples_.capacity()) {
      ++dropped_;
      return;
    }
    samples_.push_back(telemetry_sample(state));
    truths_.push_back(truth_ == nullptr ? TruthSampleOf<N>{}
                                        : TruthSampleOf<N>{truth_->x_m(), truth_->v_m_per_s(),
                                                           truth_->motor_force_N(), truth_->hand_force_N()});
  }

  std::vector<TelemetrySampleOf<N>>& samples() { return samples_; }
  std::vector<TruthSampleOf<N>>& truths() { return truths_; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  const SimulationTruthOf<N>* truth_;
  std::vector<TelemetrySampleOf<N>> samples_;
  std::vector<TruthSampleOf<N>> truths_;
  std::uint64_t dropped_{};
};

template <int N>
struct RecordedRunOf {
  WatchedRun<N> run;
  std::vector<TelemetrySampleOf<N>> samples;  // one per tick, as the --log rows
  std::vector<TruthSampleOf<N>> truths;       // the simulator's state at the same ticks
  std::uint64_t dropped{};                    // ticks past the reservation (0 unless the run overran it)
};

// The ticks a run of `duration_s` at `rate_hz` keeps (with a margin for rounding).
inline std::size_t recorded_run_capacity(double duration_s, double rate_hz) {
  return static_cast<std::size_t>(std::llround(duration_s * rate_hz)) + 2;
}

// Runs `scene` (loaded from `file`) on `device` for settings.options, without a status
// line, recording every tick.
template <int N>
RecordedRunOf<N> record_run(const SceneOf<N>& scene, DeviceOf<N>& device, const std::string& file,
                            const RunSettings& settings) {
  RunRecorderOf<N> recorder(device.truth(), recorded_run_capacity(settings.options.duration_s, scene.rate_hz));
  RecordedRunOf<N> recorded;
  recorded.run = run_watched<N>(scene, device, file, settings, false, {&recorder});
  recorded.samples = std::move(recorder.samples());
  recorded.truths = std::move(recorder.truths());
  recorded.dropped = recorder.dropped();
  return recorded;
}

}  // namespace hapscene
