#pragma once
// Several tick observers of a scene with N axes behind one (live status, telemetry log, plot trace), fixed
// size: adding happens before the run, the loop only iterates.
#include <array>
#include <cstddef>

#include "engine/run/runner.hpp"

namespace hapscene {

template <int N>
class ObserverListOf final : public TickObserverOf<N> {
 public:
  // Ignores null and anything beyond the fixed capacity.
  void add(TickObserverOf<N>* observer) noexcept {
    if (observer != nullptr && count_ < observers_.size()) observers_[count_++] = observer;
  }
  void on_start(const TickStateOf<N>& state) override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_start(state);
  }
  void on_tick(const TickStateOf<N>& state) noexcept override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_tick(state);
  }
  void on_scripts(ScriptSpan running, ScriptSpan replaced) noexcept override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_scripts(running, replaced);
  }
  void on_finish(const TickStateOf<N>& state) override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_finish(state);
  }

 private:
  std::array<TickObserverOf<N>*, 8> observers_{};
  std::size_t count_{};
};

using ObserverList = ObserverListOf<1>;

}  // namespace hapscene
