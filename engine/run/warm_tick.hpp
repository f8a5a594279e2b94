#pragma once
// The real-time loop's tick starts after about a period of sleep, when other work has
// evicted its code and data from the caches: measured cold, a Lua spring's tick cost ten
// times its hot figure. wait_until() therefore sleeps to shortly before the deadline and
// spends the spin before it bringing the tick's working set back: the scene's hot part
// and its built-in effects, the tick state, and each script's Lua state (a call of a
// tiny side-effect-free function, see ScriptInstance::warm).
//
// Nothing here allocates, throws, locks or does I/O; nothing a tick reads is written.
#include <time.h>

#include <cstddef>
#include <cstdint>
#include <tuple>

#include "engine/base/clock.hpp"
#include "engine/scene/scene.hpp"
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

// Brings what the next tick of `scene` reads into the caches.
template <int N>
void warm_tick(const SceneOf<N>& scene, const TickStateOf<N>& state) noexcept {
  const auto* scene_bytes = reinterpret_cast<const unsigned char*>(&scene);
  touch_bytes(scene_bytes, static_cast<std::size_t>(reinterpret_cast<const unsigned char*>(&scene.rate_hz) - scene_bytes));
  std::apply([](const auto&... group) { (touch_bytes(group.data(), group.size() * sizeof(*group.data())), ...); },
             scene.bank.groups);
  touch_bytes(&state, sizeof state);
  for (const auto& script : state.scripts) script->warm();
}

// How long before a deadline the loop stops sleeping: the wake-up's lateness, and the
// warming, fit in it.
inline constexpr std::int64_t kSpin_ns = 50'000;

// Sleeps until kSpin_ns before `deadline_ns` on the absolute monotonic clock, calls
// `warm` once, then spins to the deadline.
template <typename Warm>
void wait_until(std::int64_t deadline_ns, Warm&& warm) noexcept {
  const std::int64_t sleep_until_ns = deadline_ns - kSpin_ns;
  if (monotonic_now_ns() < sleep_until_ns) {
    timespec until{};
    until.tv_sec = static_cast<time_t>(sleep_until_ns / 1'000'000'000);
    until.tv_nsec = static_cast<long>(sleep_until_ns % 1'000'000'000);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, nullptr) != 0) {
    }
  }
  warm();
  while (monotonic_now_ns() < deadline_ns) {
  }
}

}  // namespace hapscene
