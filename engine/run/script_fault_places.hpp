#pragma once
// Where the handle was when each script of the running scene faulted: the run summary
// reports a disabled script once, with the time of the faulting call (from the script)
// and, with this observer, the handle position of that tick. After each tick it looks at
// the running scene's instances (a flag each) and keeps the first tick each was seen
// disabled; the storage is fixed before the run. A reload starts the list again with the
// new scene's instances (a replaced version's fault is reported by the reload watcher).
#include <array>
#include <cstddef>

#include "engine/effects/script_effect.hpp"
#include "engine/run/tick_observer.hpp"

namespace hapscene {

template <int N>
class ScriptFaultPlaces final : public TickObserverOf<N> {
 public:
  struct Place {
    bool seen{};
    double t_s{};
    Axes<N> x_m{};
  };

  void on_scripts(ScriptSpan running, ScriptSpan /*replaced*/) noexcept override {
    if (running.data() == running_.data() && running.size() == running_.size()) return;
    running_ = running;
    places_.fill(Place{});
  }

  void on_tick(const TickStateOf<N>& state) noexcept override {
    const std::size_t count = std::min(running_.size(), places_.size());
    for (std::size_t i = 0; i < count; ++i) {
      if (!places_[i].seen && running_[i]->disabled()) places_[i] = Place{true, state.t_s, state.x_m};
    }
  }

  // The running scene's script `index` (scene order): where it faulted, if it did.
  const Place* place(std::size_t index) const noexcept {
    return index < places_.size() && places_[index].seen ? &places_[index] : nullptr;
  }

 private:
  ScriptSpan running_;
  std::array<Place, kMaxScriptEffects> places_{};
};

}  // namespace hapscene
