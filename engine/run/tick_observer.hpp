#pragma once
// What sees a run tick by tick: telemetry, the live status, test traces.
#include <memory>
#include <span>

#include "engine/scene/tick_state.hpp"

namespace hapscene {

// A run of script instances (a scene's, in scene order).
using ScriptSpan = std::span<const std::unique_ptr<ScriptInstance>>;

// Sees every tick after the device write: on_tick must not allocate, lock or do I/O.
// on_start and on_finish run on the loop's thread just before the first tick and after
// the last one, outside the timed loop.
template <int N>
class TickObserverOf {
 public:
  virtual ~TickObserverOf() = default;
  virtual void on_start(const TickStateOf<N>& state) { (void)state; }
  virtual void on_tick(const TickStateOf<N>& state) noexcept = 0;
  virtual void on_finish(const TickStateOf<N>& state) { (void)state; }
  // The script instances alive (whose log another thread may drain): the running
  // scene's, and during and after a hot-reload fade the replaced scene's until it is
  // handed back to be destroyed. Called on the loop's thread before the first tick and
  // at each change (inside the loop: same rules as on_tick).
  virtual void on_scripts(ScriptSpan running, ScriptSpan replaced) noexcept {
    (void)running;
    (void)replaced;
  }
};

using TickObserver = TickObserverOf<1>;

}  // namespace hapscene
