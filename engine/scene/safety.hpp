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

namespace hapscene {

struct SafetyConfig {
  double max_force_N{};
  double slew_limit_N_per_s{};
  double workspace_min_m{};
  double workspace_max_m{};
  double soft_start_s{};
  double soft_start_threshold_N{};
  // Derived from the above and the tick period by finalise_safety().
  double max_step_N{};         // slew_limit_N_per_s * T
  double ramp_step_per_tick{}; // T / soft_start_s (1 when soft_start_s is 0)
};

// Fills the derived fields for a tick period.
void finalise_safety(double period_s, SafetyConfig* config) noexcept;

// How often each rule acted, in ticks.
struct SafetyCounters {
  std::uint64_t nonfinite_faults{};
  std::uint64_t outside_workspace_ticks{};
  std::uint64_t soft_start_ticks{};
  std::uint64_t clamped_ticks{};
  std::uint64_t slew_limited_ticks{};
  std::uint64_t position_hold_ticks{};  // ticks with an untrusted position (force held)
};

// What the loop knows of this tick's position before step(): set from the device.
enum class PositionHold : std::uint8_t {
  none,      // trusted
  ramp_out,  // stale: the force ramps to zero at the soft-start rate
  cut,       // never measured, or implausible: no force at all
};

struct SafetyState {
  bool started{};                // false until the first tick (or after restart_soft_start)
  double ramp_gain{0.0};         // soft-start gain in [0, 1]; 0 until started
  double previous_output_N{};    // for the slew limit
  PositionHold position_hold{PositionHold::none};  // set by the loop each tick
  SafetyCounters counters;
};

// Rules 1, 2 and 4: what a static probe shows as the output for a requested force.
// (Inline: it runs every tick.)
inline double apply_static_safety(const SafetyConfig& config, double x_m, double force_N,
                                  SafetyCounters* counters) noexcept {
  // The common case in three comparisons: a force within the limit (so finite: NaN and
  // infinities fail it) inside the workspace passes unchanged.
  if (std::abs(force_N) <= config.max_force_N && x_m >= config.workspace_min_m &&
      x_m <= config.workspace_max_m) [[likely]] {
    return force_N;
  }
  // 1. Non-finite force: a fault, rendered as nothing.
  if (!std::isfinite(force_N)) {
    ++counters->nonfinite_faults;
    return 0.0;
  }
  // 2. Outside the workspace: render nothing.
  if (!(x_m >= config.workspace_min_m && x_m <= config.workspace_max_m)) {
    ++counters->outside_workspace_ticks;
    return 0.0;
  }
  // 4. Clamp to the force limit.
  ++counters->clamped_ticks;
  return std::copysign(config.max_force_N, force_N);
}

// Rule 3 and an untrusted position, for a tick on which either acts (safety.cpp): returns
// the force after them.
// Untrusted position: hold the force (see PositionHold); trusted again, the soft start
// ramps it back in from the gain reached (or decides afresh after a cut).
// Soft start: decided on the first tick from the force the scene asks for there, then
// ramping (the gain is 0 until then).
[[gnu::noinline]] double apply_ramp(const SafetyConfig& config, double output_N, SafetyState* state) noexcept;

// All five rules, for one tick of a run. (Inline: it runs every tick.)
inline double apply_safety(const SafetyConfig& config, double x_m, double force_N,
                           SafetyState* state) noexcept {
  double output_N = apply_static_safety(config, x_m, force_N, &state->counters);

  // 3. (and an untrusted position) out of line: the common case is one comparison each.
  if (state->position_hold != PositionHold::none || state->ramp_gain < 1.0) [[unlikely]] {
    output_N = apply_ramp(config, output_N, state);
  }

  // 5. Slew limit against the previous output.
  const double step_N = output_N - state->previous_output_N;
  if (std::abs(step_N) > config.max_step_N) {
    output_N = state->previous_output_N + std::copysign(config.max_step_N, step_N);
    ++state->counters.slew_limited_ticks;
  }
  state->previous_output_N = output_N;
  return output_N;
}

// Makes the next tick decide again whether to ramp force in (after a scene swap).
void restart_soft_start(SafetyState* state) noexcept;

}  // namespace hapscene
