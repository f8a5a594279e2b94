#pragma once
// The real-time loop's tick starts after about a period of sleep, when other work has
// evicted its code and data from the caches and retrained the branch predictors: measured
// cold, a Lua spring's tick cost twenty times its hot figure. wait_until() therefore sleeps
// to shortly before the deadline and spends the spin before it bringing the tick back.
// Touching the tick's data alone (what the loop did first) left most of the cold cost: it
// is the code's. So TickWarmerOf replays the last tick dry: the tick's own code (step())
// on a scratch copy of the state as it was before that tick, with that tick's reading,
// the results thrown away. Each script takes part only as far as that provably changes
// nothing (ScriptInstance::begin_dry_run): a force that only reads is called again with
// the input it just had; any other is left out.
//
// Nothing here allocates, throws, locks or does I/O; nothing a tick reads is written.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>

#include "engine/run/loop_clock.hpp"
#include "engine/scene/scene.hpp"
#include "engine/scene/step.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

// Reads one byte of every cache line of [data, data + bytes).
inline void touch_bytes(const void* data, std::size_t bytes) noexcept {
  const auto* p = static_cast<const volatile unsigned char*>(data);
  unsigned char sink = 0;
  for (std::size_t i = 0; i < bytes; i += 64) sink = static_cast<unsigned char>(sink + p[i]);
  if (bytes > 0) sink = static_cast<unsigned char>(sink + p[bytes - 1]);
  asm volatile("" : : "r"(sink));
}

// Brings the data the next tick of `scene` reads into the caches (not its code): the
// scene's hot part and its built-in effects, and the tick state.
template <int N>
void touch_tick_data(const SceneOf<N>& scene, const TickStateOf<N>& state) noexcept {
  const auto* scene_bytes = reinterpret_cast<const unsigned char*>(&scene);
  touch_bytes(scene_bytes, static_cast<std::size_t>(reinterpret_cast<const unsigned char*>(&scene.rate_hz) - scene_bytes));
  std::apply([](const auto&... group) { (touch_bytes(group.data(), group.size() * sizeof(*group.data())), ...); },
             scene.bank.groups);
  touch_bytes(&state, sizeof state);
}

// Copies every value of a tick state but its scripts into `to`, whose built-in effects'
// run state must already have the size of `from`'s (the copy never allocates). Returns
// false, copying nothing, when it has not. (The bindings name every field: a field added
// to TickStateOf stops the build here until it is copied too.)
template <int N>
bool copy_tick_values(const TickStateOf<N>& from, TickStateOf<N>* to) noexcept {
  const auto& [tick, t_s, sensor, x_m, velocity_state, v_m_per_s, scripts, effect_runs, effects_force_N,
               script_calls, safety, output_N, command] = from;
  (void)scripts;
  using RunState = std::remove_cvref_t<decltype(effect_runs)>;
  if constexpr (!std::is_empty_v<RunState>) {
    if (to->effect_runs.size() != effect_runs.size()) return false;
    std::copy(effect_runs.begin(), effect_runs.end(), to->effect_runs.begin());
  }
  to->tick = tick;
  to->t_s = t_s;
  to->sensor = sensor;
  to->x_m = x_m;
  to->velocity_state = velocity_state;
  to->v_m_per_s = v_m_per_s;
  to->effects_force_N = effects_force_N;
  to->script_calls = script_calls;
  to->safety = safety;
  to->output_N = output_N;
  to->command = command;
  return true;
}

// Warms the next tick by replaying the last one dry. Made once per run, before the loop
// (it allocates its three copies of the state); warm() and note_reading() then allocate
// nothing. The loop calls warm() before each tick (once or more) and note_reading() with
// each tick's reading.
template <int N>
class TickWarmerOf {
 public:
  using Reading = typename SceneParts<N>::Reading;

  explicit TickWarmerOf(const SceneOf<N>& scene) {
    for (TickStateOf<N>* copy : {&copies_[0], &copies_[1], &scratch_}) {
      copy->sensor = make_sensor_state(scene.device_model);
      copy->effect_runs = scene.bank.make_run_state();
    }
  }
  TickWarmerOf(const TickWarmerOf&) = delete;
  TickWarmerOf& operator=(const TickWarmerOf&) = delete;

  // Before the next tick of `scene` from `state`: replays the last tick dry when it ran on
  // this scene from the copy a warm() took just before it; otherwise (the first tick, after
  // a scene swap, or when the copy does not fit) touches the tick's data and warms each
  // script on its own (ScriptInstance::warm). Then copies `state` for the next replay.
  void warm(const SceneOf<N>& scene, TickStateOf<N>& state) noexcept {
    const bool replay = last_.scene == &scene && state.tick == last_.state->tick + 1 &&
                        copy_tick_values(*last_.state, &scratch_);
    if (replay) {
      // The scripts take part through the scratch state, in their dry-run mode; the
      // vectors swap buffers, so the instances stay where the published spans see them.
      scratch_.scripts.swap(state.scripts);
      for (const auto& script : scratch_.scripts) script->begin_dry_run();
      step(scene, last_.reading, &scratch_);
      for (const auto& script : scratch_.scripts) script->end_dry_run();
      scratch_.scripts.swap(state.scripts);
    } else {
      touch_tick_data(scene, state);
      for (const auto& script : state.scripts) script->warm();
    }
    next_.scene = copy_tick_values(state, next_.state) ? &scene : nullptr;
  }

  // The reading of the tick about to run (from the state the last warm() copied, if any):
  // that copy and this reading are what the next warm() replays.
  void note_reading(const Reading& reading) noexcept {
    std::swap(last_, next_);
    last_.reading = reading;
    next_.scene = nullptr;
  }

 private:
  // A tick to replay: the state before it, its reading, and its scene (null: none).
  struct Tick {
    TickStateOf<N>* state{};
    const SceneOf<N>* scene{};
    Reading reading{};
  };
  TickStateOf<N> copies_[2];  // the states of last_ and next_ (their scripts stay empty)
  TickStateOf<N> scratch_;    // where the replay runs (holds the scripts only during it)
  Tick last_{&copies_[0]};    // the tick that ran last
  Tick next_{&copies_[1]};    // the tick about to run
};

using TickWarmer = TickWarmerOf<1>;

// How long before a deadline the loop stops sleeping: the wake-up's lateness, and the
// warming, fit in it.
inline constexpr std::int64_t kSpin_ns = 50'000;

// Sleeps on `clock` until kSpin_ns before `deadline_ns`, calls `warm` once, then spins to
// the deadline.
template <typename Warm>
void wait_until(LoopClock& clock, std::int64_t deadline_ns, Warm&& warm) noexcept {
  clock.sleep_until(deadline_ns - kSpin_ns);
  warm();
  clock.spin_until(deadline_ns);
}

}  // namespace hapscene
