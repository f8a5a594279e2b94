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
#include <utility>

#include "engine/run/tick_observer.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/step.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

// A compiled scene with its own script instances.
template <int N>
struct LoadedSceneOf {
  SceneOf<N> scene;
  ScriptList scripts;
  typename SceneParts<N>::Effects::Bank::RunState runs{};  // its built-in effects' run state
};

using LoadedScene = LoadedSceneOf<1>;

// A compiled scene ready to offer: with its own script instances and its built-in
// effects' run state (the planar shapes' proxies), made here, off the loop.
template <int N>
std::unique_ptr<LoadedSceneOf<N>> make_loaded_scene(SceneOf<N> scene) {
  auto loaded = std::make_unique<LoadedSceneOf<N>>();
  loaded->scene = std::move(scene);
  loaded->scripts = make_script_instances(loaded->scene);
  loaded->runs = loaded->scene.bank.make_run_state();
  return loaded;
}

// The two slots between the reload thread and the loop.
template <int N>
class SceneExchangeOf {
 public:
  using LoadedScene = LoadedSceneOf<N>;
  ~SceneExchangeOf();

  // Reload thread: offers a scene; false (and `next` kept) while an earlier offer has not
  // been taken yet. A run state that does not fit the scene's effects (a carrier made
  // without make_loaded_scene) is made first: the loop steps the scene with it.
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

using SceneExchange = SceneExchangeOf<1>;
// A pointer to the exchange of N axes (RunOptions holds one per N: AxesTuple).
template <int N>
using SceneExchangePointer = SceneExchangeOf<N>*;

// The loop's view: which scene to step this tick, and the cross-fade, if any.
template <int N>
class HotSwapOf {
 public:
  using LoadedScene = LoadedSceneOf<N>;
  // Outside the loop. With no exchange, scene() is always `initial`. `observer` (may be
  // null) is told the live script instances now and on every change.
  HotSwapOf(const SceneOf<N>& initial, SceneExchangeOf<N>* exchange, TickStateOf<N>* state,
            TickObserverOf<N>* observer = nullptr);
  // Outside the loop: frees whatever the loop still holds.
  ~HotSwapOf();
  HotSwapOf(const HotSwapOf&) = delete;
  HotSwapOf& operator=(const HotSwapOf&) = delete;

  // Before each tick: takes an offered scene or advances the fade. Returns the fade for
  // step(), or nullptr.
  const CrossfadeOf<N>* before_tick(TickStateOf<N>* state) noexcept;
  const SceneOf<N>& scene() const noexcept { return *scene_; }

 private:
  // Tells the observer the instances alive: the running scene's, and the one let go of.
  void publish(const TickStateOf<N>& state) noexcept;

  SceneExchangeOf<N>* exchange_;
  TickObserverOf<N>* observer_;
  const SceneOf<N>* scene_;
  std::unique_ptr<LoadedScene> initial_;  // the first scene's carrier until it is handed back
  LoadedScene* current_{nullptr};         // carrier of scene_ (null: the caller's initial)
  LoadedScene* fading_from_{nullptr};     // carrier of the scene being faded out
  LoadedScene* to_retire_{nullptr};       // faded out, waiting for a free retired slot
  CrossfadeOf<N> fade_;
  double fade_step_{};                    // weight added per tick
  bool fading_{false};
};

using HotSwap = HotSwapOf<1>;

}  // namespace hapscene
