#pragma once
// What the harness measures in one scenario run, from its tick records (after the run,
// outside the loop).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/harness/force_field.hpp"
#include "engine/harness/recorder.hpp"
#include "engine/run/runner.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// Free or held motion in a watch window: does it oscillate, at what frequency, and does
// it die out, persist (limit cycle) or grow?
struct OscillationMetrics {
  double from_s{};
  int half_cycles{};            // crossings of the rest position (with a hysteresis band)
  double frequency_Hz{};        // from the crossings; 0 with fewer than two
  double initial_amplitude_m{}; // largest |x - rest| in the first fifth of the window
  double residual_amplitude_m{};  // (max - min) / 2 of x in the last 30 % of the window
  double growth{};              // residual / initial (0 when initial is within the band)
  double rest_m{};              // mean position over the last 30 %
};

// Passivity observer. created_J = integral of motor force times true velocity, plus the
// change of the energy stored in the rendered field: positive means the rendering
// created energy. dissipated_J = the device's own viscous loss b v^2 over the ticks where
// the rendering pushed (what Colgate's bound b > K T / 2 weighs it against).
struct PassivityMetrics {
  double motor_work_J{};
  double stored_J{};
  double created_J{};
  double dissipated_J{};
  double net_J{};               // created - dissipated
  double ratio{};               // created / dissipated (0 when nothing was dissipated)
  bool grows{};                 // net > 0 and still rising over the second half
};

struct ScenarioMetrics {
  std::uint64_t ticks{};
  double duration_s{};
  // Force.
  double max_requested_N{};
  double max_output_N{};
  double max_output_x_m{};      // where (true position) and when the largest output was
  double max_output_t_s{};
  double time_at_limit_s{};
  double time_at_limit_fraction{};
  double max_slew_N_per_s{};    // largest |change of output| per tick / T
  double force_jitter_N{};      // rms of F[k] - (F[k-1] + F[k+1]) / 2
  // Capstan slip risk.
  std::uint64_t slip_force_ticks{};  // |output| > slip force
  std::uint64_t slip_step_ticks{};   // |output change within 1 ms| > slip step
  double max_step_1ms_N{};
  double slip_first_x_m{};      // where (true position) and when the first slip tick was
  double slip_first_t_s{-1.0};  // (-1: none)
  double jitter_peak_N{};       // the largest |second difference| of the command,
  double jitter_peak_x_m{};     // where and when
  double jitter_peak_t_s{};
  // Energy and oscillation.
  PassivityMetrics passivity;
  std::optional<OscillationMetrics> oscillation;
  // Walls.
  double max_penetration_m{};
  double max_penetration_x_m{};
  // Scripts (filled once scripts exist) and timing.
  std::uint64_t script_errors{};
  std::uint64_t script_budget_overruns{};
  // Each disabled script's message ("scripts/x.lua:3: attempt to ..."), with when and
  // where it faulted ("t 0.512 s, x 10.02 mm"; empty when unknown).
  struct ScriptFaultSeen {
    std::string message;
    std::string where;
    std::string text() const { return where.empty() ? message : message + " (" + where + ")"; }
  };
  std::vector<ScriptFaultSeen> script_faults;
  double compute_p50_s{};
  double compute_p99_s{};
  double compute_max_s{};
  SafetyCounters safety;
};

// At most this much energy created (0.01 mJ), the passivity check does not judge a
// scenario, and growing net energy does not count. No environment key sets it.
inline constexpr double kMinJudgedEnergy_J = 1e-5;

// Measures one run; `final_x_m` is the true position after the last tick.
ScenarioMetrics measure_run(const Scene& scene, const ForceField& field,
                            const std::vector<TickRecord>& records, double final_x_m,
                            const RunSummary& summary, std::optional<double> watch_from_s);

// The oscillation metrics of true positions from `from_s` on; `band_m` is the hysteresis.
OscillationMetrics measure_oscillation(const std::vector<TickRecord>& records, double from_s,
                                       double band_m);

}  // namespace hapscene
