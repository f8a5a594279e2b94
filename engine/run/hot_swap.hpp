#pragma once
// Hot reload, the loop's side. A reload thread parses and compiles a changed environment
// off the loop and offers it (scene plus fresh script instances); the loop takes it at a
// tick boundary and cross-fades from the old scene's force to the new one's over the
// new scene's soft-start time, then hands the old one back to be destroyed off the loop.
// The hand-over is two atomic pointer slots: the loop never allocates, frees or waits.
//
// Script log messages are drained by another thread (the live status) while the loop
// swaps instances: the HotSwap tells the run's observer which instances are alive
// (TickObserver::on_scripts) whenever that changes, and a scene is handed back to be
// destroyed only after it was left out of that list.
#include <atomic>
#include <memory>

#include "engine/run/tick_observer.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/step.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

// A compiled scene with its own script instances.
struct LoadedScene {
  Scene scene;
  ScriptList scripts;
};

// The two slots between the reload thread and the loop.
class SceneExchange {
 public:
  ~SceneExchange();

  // Reload thread: offers a scene; false (and `next` untouched) while an earlier offer
  // has not been taken yet.
  bool offer(std::unique_ptr<LoadedScene>& next);
  // Reload thread: a scene the loop is done with, to destroy here; null when none.
  std::unique_ptr<LoadedScene> take_retired();
  // How many offers the loop has taken.
  std::uint64_t swaps() const noexcept { return swaps_.load(std::memory_order_relaxed); }

  // Loop thread.
  LoadedScene* take_offer() noexcept;
  bool retire_slot_free() const noexcept { return retired_.load(std::memory_order_acquire) == nullptr; }
  bool retire(LoadedScene* done) noexcept;  // false while the slot is still full

 private:
  std::atomic<LoadedScene*> offered_{nullptr};
  std::atomic<LoadedScene*> retired_{nullptr};
  std::atomic<std::uint64_t> swaps_{0};
};

// The loop's view: which scene to step this tick, and the cross-fade, if any.
class HotSwap {
 public:
  // Outside the loop. With no exchange, scene() is always `initial`. `observer` (may be
  // null) is told the live script instances now and on every change.
  HotSwap(const Scene& initial, SceneExchange* exchange, TickState* state,
          TickObserver* observer = nullptr);
  // Outside the loop: frees whatever the loop still holds.
  ~HotSwap();
  HotSwap(const HotSwap&) = delete;
  HotSwap& operator=(const HotSwap&) = delete;

  // Before each tick: takes an offered scene or advances the fade. Returns the fade for
  // step(), or nullptr.
  const Crossfade* before_tick(TickState* state) noexcept;
  const Scene& scene() const noexcept { return *scene_; }

 private:
  // Tells the observer the instances alive: the running scene's, and the one let go of.
  void publish(const TickState& state) noexcept;

  SceneExchange* exchange_;
  TickObserver* observer_;
  const Scene* scene_;
  std::unique_ptr<LoadedScene> initial_;  // the first scene's carrier until it is handed back
  LoadedScene* current_{nullptr};         // carrier of scene_ (null: the caller's initial)
  LoadedScene* fading_from_{nullptr};     // carrier of the scene being faded out
  LoadedScene* to_retire_{nullptr};       // faded out, waiting for a free retired slot
  Crossfade fade_;
  double fade_step_{};                    // weight added per tick
  bool fading_{false};
};

}  // namespace hapscene
