#pragma once
// Several tick observers behind one (live status, telemetry log, plot trace), fixed
// size: adding happens before the run, the loop only iterates.
#include <array>
#include <cstddef>

#include "engine/run/runner.hpp"

namespace hapscene {

class ObserverList final : public TickObserver {
 public:
  // Ignores null and anything beyond the fixed capacity.
  void add(TickObserver* observer) noexcept {
    if (observer != nullptr && count_ < observers_.size()) observers_[count_++] = observer;
  }
  void on_start(const TickState& state) override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_start(state);
  }
  void on_tick(const TickState& state) noexcept override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_tick(state);
  }
  void on_scripts(ScriptSpan running, ScriptSpan replaced) noexcept override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_scripts(running, replaced);
  }
  void on_finish(const TickState& state) override {
    for (std::size_t i = 0; i < count_; ++i) observers_[i]->on_finish(state);
  }

 private:
  std::array<TickObserver*, 8> observers_{};
  std::size_t count_{};
};

}  // namespace hapscene
