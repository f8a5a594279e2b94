#pragma once
// The safety stage: applied last, to the sum of all effects (built-in and scripted), and
// not bypassable by any effect. In order:
//   1. a non-finite force becomes 0 N and is counted as a fault;
//   2. outside the workspace limits the force is 0 N (the position may be wrong, e.g.
//      after capstan slip, so nothing is rendered there);
//   3. soft start: when a run starts (or a scene is swapped) with the handle in a force
//      field stronger than the threshold, force ramps in linearly over soft_start_s;
//   4. clamp to max_force_N (the lower of the device's and the environment's);
//   5. slew limit: the output changes by at most slew_limit_N_per_s * T per tick.
// Before 3, an untrusted position (a device on a link says so, see PositionStatus) holds
// the force: none at all when nothing trustworthy was measured, else ramped out at the
// soft-start rate; when the position is trusted again force ramps back in (soft start).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "engine/base/axes.hpp"

namespace hapscene {

// The limits for a scene with N axes. With more than one axis the force limit and the
// slew limit act on the force vector's magnitude (keeping its direction) and the workspace
// is a box in task space.
struct NoPolygon {};

template <int N>
struct SafetyConfigOf {
  double max_force_N{};
  double slew_limit_N_per_s{};
  Axes<N> workspace_min_m{};
  Axes<N> workspace_max_m{};
  double soft_start_s{};
  double soft_start_threshold_N{};
  // Derived from the above and the tick period by finalise_safety().
  double max_step_N{};         // slew_limit_N_per_s * T
  double ramp_step_per_tick{}; // T / soft_start_s (1 when soft_start_s is 0)
  // More than one axis: when not empty, the device's workspace polygon (simple, checked
  // at load). The workspace is then the intersection of the box workspace_min_m/max_m
  // (the polygon's bounding box, or the environment's narrower box) and the polygon:
  // a position must pass both tests, the box first.
  [[no_unique_address]] std::conditional_t<(N > 1), std::vector<AxisVector<(N > 1 ? N : 2)>>, NoPolygon>
      workspace_polygon_m{};
};

using SafetyConfig = SafetyConfigOf<1>;

// Fills the derived fields for a tick period.
template <int N>
void finalise_safety(double period_s, SafetyConfigOf<N>* config) noexcept {
  config->max_step_N = config->slew_limit_N_per_s * period_s;
  config->ramp_step_per_tick = config->soft_start_s > 0.0 ? period_s / config->soft_start_s : 1.0;
}

// How often each rule acted, in ticks.
struct SafetyCounters {
  std::uint64_t nonfinite_faults{};
  std::uint64_t outside_workspace_ticks{};
  std::uint64_t soft_start_ticks{};
  std::uint64_t clamped_ticks{};
  std::uint64_t slew_limited_ticks{};
  std::uint64_t position_hold_ticks{};  // ticks with an untrusted position (force held)
  // Linkages (more than one axis):
  std::uint64_t pose_hold_ticks{};      // near a singular pose, or one the linkage cannot take
  std::uint64_t motor_saturated_ticks{}; // a motor saturated: both commands scaled alike
};

// What the loop knows of this tick's position before step(): set from the device.
enum class PositionHold : std::uint8_t {
  none,      // trusted
  ramp_out,  // stale: the force ramps to zero at the soft-start rate
  cut,       // never measured, or implausible: no force at all
};

template <int N>
struct SafetyStateOf {
  bool started{};                // false until the first tick (or after restart_soft_start)
  double ramp_gain{0.0};         // soft-start gain in [0, 1]; 0 until started
  Axes<N> previous_output_N{};   // for the slew limit
  PositionHold position_hold{PositionHold::none};  // set by the loop each tick
  SafetyCounters counters;
};

using SafetyState = SafetyStateOf<1>;

// True when p is inside the simple polygon (crossing number; on an edge may go either way).
bool inside_polygon(const std::vector<Vec2>& polygon_m, const Vec2& p_m) noexcept;

// The workspace test: inside the interval, or the box (every axis within its limits) and,
// when the workspace is a polygon, inside it.
inline bool within_workspace(const SafetyConfigOf<1>& config, double x_m) noexcept {
  return x_m >= config.workspace_min_m && x_m <= config.workspace_max_m;
}
// (Inline whatever the compiler's estimate: it runs every tick, and as a call it cost the
// planar tick a call's set-up and spills; the polygon test stays out of line.)
template <int N>
[[gnu::always_inline]] inline bool within_workspace(const SafetyConfigOf<N>& config,
                                                   const AxisVector<N>& x_m) noexcept {
  for (int i = 0; i < N; ++i) {
    if (!(x_m[i] >= config.workspace_min_m[i] && x_m[i] <= config.workspace_max_m[i])) return false;
  }
  return config.workspace_polygon_m.empty() || inside_polygon(config.workspace_polygon_m, x_m);
}

// norm(value) <= limit, decided exactly as that expression decides it, but with the square
// root of a vector's length taken only near the limit: a squared length clearly below the
// squared limit (by more than rounding can move it, a relative 1e-15) is within it.
inline bool within_magnitude(double value, double limit) noexcept { return norm(value) <= limit; }
template <int N>
inline bool within_magnitude(const AxisVector<N>& value, double limit) noexcept {
  constexpr double kClearlyBelow = 1.0 - 1e-15;
  const double length_sq = dot(value, value);
  if (length_sq <= limit * limit * kClearlyBelow) [[likely]] return true;
  return norm(value) <= limit;
}
// norm(value) > limit, likewise (for a finite value the negation of the above).
inline bool exceeds_magnitude(double value, double limit) noexcept { return norm(value) > limit; }
template <int N>
inline bool exceeds_magnitude(const AxisVector<N>& value, double limit) noexcept {
  constexpr double kClearlyBelow = 1.0 - 1e-15;
  const double length_sq = dot(value, value);
  if (length_sq <= limit * limit * kClearlyBelow) [[likely]] return false;
  return norm(value) > limit;
}

// `value` with its magnitude limited to `limit` (> 0), keeping its sign or direction.
inline double limit_magnitude(double value, double limit) noexcept { return std::copysign(limit, value); }
// A vector too long for its squared length to be a double (past about 1e154) is scaled
// down by its largest component first, so it is clamped, not zeroed; and rounding never
// leaves the result past the limit (a last step down by an ulp when it would).
template <int N>
inline AxisVector<N> limit_magnitude(const AxisVector<N>& value, double limit) noexcept {
  double length = norm(value);
  AxisVector<N> direction = value;
  if (!std::isfinite(length)) [[unlikely]] {
    double largest = 0.0;
    for (int i = 0; i < N; ++i) largest = std::fmax(largest, std::fabs(value[i]));
    direction = value * (1.0 / largest);
    length = norm(direction);
  }
  AxisVector<N> limited = direction * (limit / length);
  while (norm(limited) > limit) [[unlikely]] limited *= 1.0 - 0x1p-53;
  return limited;
}

// Rules 1, 2 and 4: what a static probe shows as the output for a requested force.
// (Inline: it runs every tick.)
template <int N>
[[gnu::always_inline]] inline Axes<N> apply_static_safety(const SafetyConfigOf<N>& config, const Axes<N>& x_m,
                                   const Axes<N>& force_N, SafetyCounters* counters) noexcept {
  // The common case in three comparisons (per axis): a force within the limit (so finite:
  // NaN and infinities fail it) inside the workspace passes unchanged.
  const bool inside = within_workspace(config, x_m);
  if (within_magnitude(force_N, config.max_force_N) && inside) [[likely]] {
    return force_N;
  }
  // 1. Non-finite force: a fault, rendered as nothing.
  if (!all_finite(force_N)) {
    ++counters->nonfinite_faults;
    return Axes<N>{};
  }
  // 2. Outside the workspace: render nothing.
  if (!inside) {
    ++counters->outside_workspace_ticks;
    return Axes<N>{};
  }
  // 4. Clamp to the force limit.
  ++counters->clamped_ticks;
  return limit_magnitude(force_N, config.max_force_N);
}

// Rule 3 and an untrusted position, for a tick on which either acts (safety.cpp): returns
// the force after them.
// Untrusted position: hold the force (see PositionHold); trusted again, the soft start
// ramps it back in from the gain reached (or decides afresh after a cut).
// Soft start: decided on the first tick from the force the scene asks for there, then
// ramping (the gain is 0 until then).
template <int N>
[[gnu::noinline]] Axes<N> apply_ramp(const SafetyConfigOf<N>& config, Axes<N> output_N,
                                     SafetyStateOf<N>* state) noexcept;

// Whether rule 3 or a held position acts on this tick (apply_ramp is needed).
template <int N>
inline bool ramp_acts(const SafetyStateOf<N>& state) noexcept {
  return state.position_hold != PositionHold::none || state.ramp_gain < 1.0;
}

// All five rules, for one tick of a run. (Inline: it runs every tick.) kRampPossible
// false: the caller knows ramp_acts() is false on this tick.
template <int N, bool kRampPossible = true>
[[gnu::always_inline]] inline Axes<N> apply_safety(const SafetyConfigOf<N>& config, const Axes<N>& x_m,
                            const Axes<N>& force_N, SafetyStateOf<N>* state) noexcept {
  Axes<N> output_N = apply_static_safety(config, x_m, force_N, &state->counters);

  // 3. (and an untrusted position) out of line: the common case is one comparison each.
  if (kRampPossible && ramp_acts(*state)) [[unlikely]] {
    output_N = apply_ramp(config, output_N, state);
  }

  // 5. Slew limit against the previous output.
  const Axes<N> step_N = output_N - state->previous_output_N;
  if (exceeds_magnitude(step_N, config.max_step_N)) {
    output_N = state->previous_output_N + limit_magnitude(step_N, config.max_step_N);
    ++state->counters.slew_limited_ticks;
  }
  state->previous_output_N = output_N;
  return output_N;
}

// Makes the next tick decide again whether to ramp force in (after a scene swap).
template <int N>
void restart_soft_start(SafetyStateOf<N>* state) noexcept {
  state->started = false;
  state->ramp_gain = 0.0;
}

}  // namespace hapscene
