#pragma once
// The finite range of every physical number an environment or device profile may give
// (docs/reference/environments.md and docs/reference/devices.md list them). They are
// generous: far beyond anything a Hapkit-sized device can render or be, yet small enough
// that every product the engine forms (stiffness x length, damping x speed) stays finite,
// so no absurd value from a file reaches the tick.
#include "engine/base/range.hpp"

namespace hapscene::ranges {

// Positions (walls, spring centres, texture offsets, workspaces, end stops) and texture
// lengths: within 1 km. The harness samples at most 1 m of workspace, so a length meant in
// millimetres but written as a plain number (metres) within that 1 m is at most 1000 m:
// it still loads, and the loader warns about the wall it misplaces, hinting "mm".
inline constexpr Range kPosition_m{-1000.0, 1000.0};
inline constexpr Range kLength_m{0.0, 1000.0};
// Texture field width: at least 1 um (a Hapkit count is about 12 um; a finer field can
// never be felt, and the period must stay far above a double's resolution of a position).
inline constexpr Range kFieldWidth_m{1e-6, 1000.0};
// 10 MN/m = 10 N/um: 100 times the stiffest wall a sampled Hapkit renders at 100 kHz.
inline constexpr Range kStiffness_N_per_m{0.0, 1e7};
inline constexpr Range kPositiveStiffness_N_per_m{0.0, 1e7, true};
// 10 kN*s/m: 10 N at 1 mm/s; the stability sweep finds dampers above 100 N*s/m unstable.
inline constexpr Range kDamping_N_s_per_m{0.0, 1e4};
// Forces: 1 kN, two orders above a desktop haptic device's motor.
inline constexpr Range kForce_N{0.0, 1000.0};
inline constexpr Range kPositiveForce_N{0.0, 1000.0, true};
// Slew: enough to step the largest force (1 kN) within one tick at the highest rate (100 kHz).
inline constexpr Range kPositiveSlew_N_per_s{0.0, 1e8, true};
// Durations such as a soft start: a minute.
inline constexpr Range kDuration_s{0.0, 60.0};
inline constexpr Range kPositiveDuration_s{0.0, 60.0, true};
// Filter cut-offs: up to 1 MHz, ten times the highest tick rate.
inline constexpr Range kCutoff_Hz{0.0, 1e6, true};

// A friction coefficient: 10 is far beyond rubber on rubber (about 1 to 2).
inline constexpr Range kFrictionCoefficient{0.0, 10.0};
// A direction's components before normalising (any scale, finite and far from overflow).
inline constexpr Range kDirectionComponent{-1e6, 1e6};
// Device profiles: a sensor's slope in degrees per count (its magnitude: at least 1e-6),
// a motor constant, and the sensor's noise in counts.
inline constexpr Range kDegPerCountMagnitude{1e-6, 10.0};
inline constexpr Range kMotorConstant_N_m{1e-6, 100.0};
inline constexpr Range kNoise_counts{0.0, 1000.0};

// A circle's radius: positive, within the range of positions.
inline constexpr Range kRadius_m{0.0, 1000.0, true};

}  // namespace hapscene::ranges
