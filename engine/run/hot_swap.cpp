#include "engine/run/hot_swap.hpp"

#include <algorithm>

namespace hapscene {

template <int N>
SceneExchangeOf<N>::~SceneExchangeOf() {
  delete offered_.exchange(nullptr);
  delete retired_.exchange(nullptr);
}

template <int N>
bool SceneExchangeOf<N>::offer(std::unique_ptr<LoadedScene>& next) {
  if constexpr (requires { next->scene.bank.proxy_count(); }) {
    if (next->runs.size() != next->scene.bank.proxy_count()) next->runs = next->scene.bank.make_run_state();
  }
  LoadedScene* expected = nullptr;
  if (!offered_.compare_exchange_strong(expected, next.get(), std::memory_order_acq_rel)) return false;
  next.release();
  return true;
}

template <int N>
std::unique_ptr<LoadedSceneOf<N>> SceneExchangeOf<N>::take_retired() {
  return std::unique_ptr<LoadedScene>(retired_.exchange(nullptr, std::memory_order_acq_rel));
}

template <int N>
LoadedSceneOf<N>* SceneExchangeOf<N>::take_offer() noexcept {
  if (offered_.load(std::memory_order_relaxed) == nullptr) return nullptr;
  LoadedScene* next = offered_.exchange(nullptr, std::memory_order_acq_rel);
  if (next != nullptr) swaps_.fetch_add(1, std::memory_order_relaxed);
  return next;
}

template <int N>
bool SceneExchangeOf<N>::retire(LoadedScene* done) noexcept {
  LoadedScene* expected = nullptr;
  return retired_.compare_exchange_strong(expected, done, std::memory_order_acq_rel);
}

template <int N>
HotSwapOf<N>::HotSwapOf(const SceneOf<N>& initial, SceneExchangeOf<N>* exchange, TickStateOf<N>* state,
                        TickObserverOf<N>* observer)
    : exchange_(exchange), observer_(observer), scene_(&initial) {
  publish(*state);
  if (exchange_ == nullptr) return;
  // The first scene gets a carrier too (its scripts stay in the state), so every scene
  // the loop lets go of can be retired the same way.
  initial_ = std::make_unique<LoadedScene>();
}

template <int N>
HotSwapOf<N>::~HotSwapOf() {
  for (LoadedScene* carrier : {current_, fading_from_, to_retire_}) {
    if (carrier != initial_.get()) delete carrier;
  }
}

template <int N>
void HotSwapOf<N>::publish(const TickStateOf<N>& state) noexcept {
  if (observer_ == nullptr) return;
  const LoadedScene* other = fading_from_ != nullptr ? fading_from_ : to_retire_;
  observer_->on_scripts(ScriptSpan(state.scripts),
                        other != nullptr ? ScriptSpan(other->scripts) : ScriptSpan());
}

// Invariant: the current scene's instances live in state->scripts; a carrier's `scripts`
// holds the instances of the scene it carries only once that scene is let go of.
template <int N>
const CrossfadeOf<N>* HotSwapOf<N>::before_tick(TickStateOf<N>* state) noexcept {
  if (exchange_ == nullptr) return nullptr;

  // Hand back the scene let go of, once the reload thread has collected the last one:
  // first out of the published list, then into the slot (only this thread fills it).
  if (to_retire_ != nullptr && exchange_->retire_slot_free()) {
    LoadedScene* done = to_retire_;
    to_retire_ = nullptr;
    publish(*state);
    exchange_->retire(done);
  }

  if (!fading_) {
    LoadedScene* next = to_retire_ == nullptr ? exchange_->take_offer() : nullptr;
    if (next == nullptr) return nullptr;
    // Start fading from the running scene to `next`: swap the instances so the state
    // holds the new scene's and the old carrier holds the old ones.
    fading_from_ = current_ != nullptr ? current_ : initial_.get();
    fade_.from = scene_;
    std::swap(state->scripts, next->scripts);
    std::swap(next->scripts, fading_from_->scripts);
    fade_.from_scripts = &fading_from_->scripts;
    std::swap(state->effect_runs, next->runs);
    std::swap(next->runs, fading_from_->runs);
    fade_.from_runs = &fading_from_->runs;
    scene_ = &next->scene;
    current_ = next;
    fade_.weight_to = 0.0;
    const double fade_s = std::max(0.1, scene_->safety.soft_start_s);
    fade_step_ = scene_->period_s / fade_s;
    fading_ = true;
    publish(*state);
    return &fade_;
  }

  // Advance the fade; when it is complete, let the old scene go. The first scene's
  // carrier (its Scene belongs to the caller) holds only its instances: it goes back too.
  fade_.weight_to = std::min(1.0, fade_.weight_to + fade_step_);
  if (fade_.weight_to < 1.0) return &fade_;
  fading_ = false;
  to_retire_ = fading_from_;
  if (fading_from_ == initial_.get()) (void)initial_.release();
  fading_from_ = nullptr;
  return nullptr;
}

// The axis counts scenes are compiled for.
#define HAPSCENE_HOT_SWAP(N)      \
  template class SceneExchangeOf<N>; \
  template class HotSwapOf<N>;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_HOT_SWAP)
#undef HAPSCENE_HOT_SWAP

}  // namespace hapscene
