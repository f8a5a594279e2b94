#pragma once
// Every numeric option of every command, with the values it accepts. The commands take
// their numbers through these definitions only (Arguments::take), so a value outside its
// range is refused in one place, with exit code 2 and a message naming the option and
// the range. The ranges are generous for real use and keep every allocation and loop a
// value drives bounded (docs/reference/commands.md lists them).
#include <cstdint>
#include <limits>

#include "engine/cli/arguments.hpp"
#include "engine/harness/option_ranges.hpp"

namespace hapscene::option {

inline constexpr double kDay_s = 24.0 * 3600.0;

// An option whose range the harness owns (test specs check the same values).
constexpr QuantityOption from_range(std::string_view name, const ValueRange& range) {
  return {name, range.quantity, range.min, range.max, range.min_exclusive, range.unit};
}

// run
inline constexpr WholeOption baud{"baud", 1, 100'000'000, "a positive whole number of bits per second"};
inline constexpr QuantityOption duration{"duration", Quantity::time_s, 0.0, kDay_s, true};
inline constexpr QuantityOption run_hand_stiffness{"hand-stiffness", Quantity::stiffness_N_per_m, 0.0, 1e6};
inline constexpr QuantityOption run_hand_damping{"hand-damping", Quantity::damping_N_s_per_m, 0.0, 1e4};
inline constexpr QuantityOption hold{"hold", Quantity::length_m, -1.0, 1.0};
inline constexpr QuantityOption release{"release", Quantity::time_s, 0.0, kDay_s};
inline constexpr QuantityOption run_start{"start", Quantity::length_m, -1.0, 1.0};

// devices: how long to wait for boards to answer the handshake (an Uno-style board resets
// when its port opens and answers after its bootloader's wait, about 1 s)
inline constexpr QuantityOption devices_timeout{"timeout", Quantity::time_s, 0.0, 30.0, true};

// calibrate: how long the travel step lasts, and the direction pulse's largest force
inline constexpr QuantityOption calibrate_travel_time{"travel-time", Quantity::time_s, 1.0, 300.0};
inline constexpr QuantityOption calibrate_pulse_force{"pulse-force", Quantity::force_N, 0.05, 2.0};

// run, validate, plot: the sensor noise and its seed
inline constexpr QuantityOption noise = from_range("noise", value_range::noise);
inline constexpr WholeOption seed{"seed", 0, std::numeric_limits<std::uint64_t>::max()};

// validate, plot: the virtual hand and the free scenario's start
inline constexpr QuantityOption hand_stiffness = from_range("hand-stiffness", value_range::hand_stiffness);
inline constexpr QuantityOption hand_damping = from_range("hand-damping", value_range::hand_damping);
inline constexpr QuantityOption hand_mass = from_range("hand-mass", value_range::hand_mass);
inline constexpr QuantityOption free_start = from_range("start", value_range::free_start);

// plot on a 2-DOF environment: arrows along the workspace's longer side, the figure's width
inline constexpr WholeOption plot_grid{"grid", 2, 200, "a whole number of arrows"};
inline constexpr WholeOption plot_width{"width", 400, 4000, "a whole number of pixels"};

// probe: START and STOP of --x, its STEP (at least kMinProbeStep_m in size), and --v
inline constexpr QuantityOption probe_position = from_range("x", value_range::probe_position);
inline constexpr QuantityOption probe_step{"x", Quantity::length_m, -1000.0, 1000.0};
inline constexpr double kMinProbeStep_m = 1e-9;
inline constexpr long long kMaxProbePoints = 1'000'000;
inline constexpr QuantityOption probe_velocity = from_range("v", value_range::probe_velocity);
// probe --t: the run time each point is evaluated at (from fresh script instances)
inline constexpr QuantityOption probe_time{"t", Quantity::time_s, 0.0, kDay_s};

// test: specs run at once in processes of their own (0: one per core), and how long one may take
inline constexpr WholeOption test_jobs{"jobs", 0, 256, "a whole number of processes (0: one per core)"};
inline constexpr QuantityOption test_spec_timeout{"spec-timeout", Quantity::time_s, 0.0, kDay_s, true};

// bench (tick cost tables)
inline constexpr QuantityOption bench_seconds{"seconds", Quantity::time_s, 0.0, 600.0, true};
inline constexpr WholeOption bench_passes{"passes", 1, 1000};
// bench --soak and --callgrind
inline constexpr WholeOption soak_ticks{"ticks", 10'000, 10'000'000'000ull};
inline constexpr WholeOption callgrind_ticks{"ticks", 0, 1'000'000'000};
// bench --stress and --accuracy
inline constexpr QuantityOption stress_noise{"noise", Quantity::dimensionless, 0.0, 100.0, false, "counts"};
inline constexpr QuantityOption stress_rate{"rate", Quantity::frequency_Hz, 100.0, 100'000.0};
inline constexpr QuantityOption accuracy_rate{"rate", Quantity::frequency_Hz, 250.0, 20'000.0};
inline constexpr WholeOption accuracy_axes{"axes", 1, 2, "1 (the Hapkit's rows) or 2 (the planar plant's)"};

}  // namespace hapscene::option
