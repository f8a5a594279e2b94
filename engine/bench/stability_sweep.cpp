#include "engine/bench/stability_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "engine/devices/kinematics.hpp"
#include "engine/devices/noise.hpp"
#include "engine/harness/validate.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/velocity.hpp"

namespace hapscene {
namespace {

constexpr int kBisections = 12;  // (5000x range)^(1/4096): about 0.2 % per step

// Whether every check named in `names` passes in every scenario of the report; else the
// first failing "scenario/check".
std::string first_failure(const ValidationReport& report, std::initializer_list<std::string_view> names) {
  for (const ScenarioResult& scenario : report.scenarios) {
    for (const CheckResult& check : scenario.checks) {
      for (const std::string_view name : names) {
        if (check.name == name && !check.pass) return scenario.scenario.name + "/" + check.name;
      }
    }
  }
  return {};
}

// The largest value in [low, high] for which `passes` holds, by bisection in log space
// (assumes it passes at low and fails somewhere above). Sets *above when high passes.
double largest_passing(double low, double high, const std::function<bool(double)>& passes, bool* above) {
  *above = passes(high);
  if (*above) return high;
  if (!passes(low)) return 0.0;
  for (int i = 0; i < kBisections; ++i) {
    const double mid = std::sqrt(low * high);
    (passes(mid) ? low : high) = mid;
  }
  return low;
}

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

DeviceProfile stress_profile() { return load_device_profile("hapkit3", "."); }

namespace {

// The largest amplitude of motion left at the end of any watched scenario (hold, release).
double largest_residual_m(const ValidationReport& report) {
  double residual_m = 0.0;
  for (const ScenarioResult& scenario : report.scenarios) {
    if (scenario.metrics.oscillation) {
      residual_m = std::max(residual_m, scenario.metrics.oscillation->residual_amplitude_m);
    }
  }
  return residual_m;
}

// One wall at 10 mm at `rate_hz`, judged by the press, hold and release scenarios, on
// `profile` (its Coulomb friction as given).
WallLimits wall_limits(const DeviceProfile& profile, double rate_hz) {
  const HarnessOptions options;  // the harness's hand: 200 N/m, 2 N*s/m, 20 g
  const double count_m = std::abs(counts_to_position_m(profile, 1.0) - counts_to_position_m(profile, 0.0));
  const auto report_for = [&](double k) {
    Scene scene = load_environment_text(
        R"({"rate_hz": )" + number(rate_hz) + R"(, "effects": [{"type": "wall", "position": 0.01, "stiffness": )" +
            number(k) + R"(, "solid": "above"}]})",
        "stress.json", ".");
    scene.device = profile;
    return validate_scene(scene, {ScenarioKind::press, ScenarioKind::hold, ScenarioKind::release}, options);
  };
  WallLimits l;
  l.coulomb_N = profile.plant.coulomb_N;
  const PassivityBound bound = passivity_bound(profile, 1.0 / rate_hz);
  l.bound_N_per_m = bound.N_per_m;
  l.bound_name = bound.name;
  l.bound_coulomb_N_per_m = 2.0 * profile.plant.coulomb_N / count_m;
  l.passive_N_per_m = largest_passing(
      200.0, 1e6, [&](double k) { return first_failure(report_for(k), {"passivity"}).empty(); },
      &l.passive_above_range);
  l.stable_N_per_m = largest_passing(
      200.0, 1e6, [&](double k) { return first_failure(report_for(k), {"limit_cycle", "growth"}).empty(); },
      &l.stable_above_range);
  // Quiet: stable, and the handle ends still to within one sensor count.
  l.quiet_N_per_m = largest_passing(
      200.0, 1e6,
      [&](double k) {
        const ValidationReport report = report_for(k);
        return first_failure(report, {"limit_cycle", "growth"}).empty() && largest_residual_m(report) <= count_m;
      },
      &l.quiet_above_range);
  return l;
}

}  // namespace

std::vector<StiffnessLimits> sweep_wall_stiffness(const std::vector<double>& rates_hz) {
  const DeviceProfile profile = stress_profile();
  DeviceProfile frictionless = profile;
  frictionless.plant.coulomb_N = 0.0;
  const HarnessOptions options;
  const double b = profile.plant.viscous_N_s_per_m;
  std::vector<StiffnessLimits> limits;
  for (const double rate_hz : rates_hz) {
    StiffnessLimits l;
    l.rate_hz = rate_hz;
    l.bound_2b_over_T = 2.0 * b * rate_hz;
    l.bound_with_hand = 2.0 * (b + options.hand_damping_N_s_per_m) * rate_hz;
    l.with_coulomb = wall_limits(profile, rate_hz);
    l.without_coulomb = wall_limits(frictionless, rate_hz);
    limits.push_back(l);
  }
  return limits;
}

std::vector<DampingLimit> sweep_damping(double rate_hz, double noise_counts) {
  HarnessOptions options;
  options.noise_counts = noise_counts;
  std::vector<DampingLimit> limits;
  for (const std::string_view estimator : kVelocityEstimatorNames) {
    const auto report_for = [&](double damping) {
      const Scene scene = load_environment_text(
          R"({"rate_hz": )" + number(rate_hz) + R"(, "velocity": {"estimator": ")" + std::string(estimator) +
              R"("}, "effects": [{"type": "damper", "damping": )" + number(damping) + "}]}",
          "stress.json", ".");
      return validate_scene(scene, {ScenarioKind::hold, ScenarioKind::shake}, options);
    };
    DampingLimit l;
    l.estimator = std::string(estimator);
    l.smooth_N_s_per_m = largest_passing(
        0.01, 100.0,
        [&](double damping) { return first_failure(report_for(damping), {"jitter", "limit_cycle", "growth"}).empty(); },
        &l.above_range);
    if (!l.above_range) {
      l.first_failure = first_failure(report_for(l.smooth_N_s_per_m * 1.05), {"jitter", "limit_cycle", "growth"});
    }
    limits.push_back(l);
  }
  return limits;
}

}  // namespace hapscene

namespace hapscene {

std::vector<EstimatorQuality> measure_estimators(double rate_hz, double noise_counts) {
  const DeviceProfile profile = stress_profile();
  const double count_m = std::abs(counts_to_position_m(profile, 1.0) - counts_to_position_m(profile, 0.0));
  const double period_s = 1.0 / rate_hz;
  std::vector<EstimatorQuality> qualities;
  for (std::size_t i = 0; i < std::size(kVelocityEstimatorNames); ++i) {
    VelocityEstimatorConfig config;
    config.kind = static_cast<VelocityEstimatorKind>(i);
    config.lowpass_alpha = lowpass_alpha_for(config.cutoff_Hz, period_s);
    EstimatorQuality q;
    q.estimator = std::string(kVelocityEstimatorNames[i]);

    // Noise: the handle at rest, the reading rounded to whole counts, 2 s after 0.5 s.
    {
      GaussianNoise noise(1);
      VelocityState state;
      const auto warm = static_cast<int>(0.5 * rate_hz);
      const auto ticks = static_cast<int>(2.0 * rate_hz);
      double sum_m2_per_s2 = 0.0;
      for (int k = 0; k < warm + ticks; ++k) {
        const double x_m = count_m * std::round(noise_counts * noise.next());
        const double v_m_per_s = estimate_velocity(config, rate_hz, x_m, &state);
        if (k >= warm) sum_m2_per_s2 += v_m_per_s * v_m_per_s;
      }
      q.noise_rms_m_per_s = std::sqrt(sum_m2_per_s2 / ticks);
    }

    // Delay and gain: x = A sin(w t) at 5 Hz, unquantized; the estimate projected on the
    // true velocity's cos and sin over the last 1 s (whole periods) of 2 s.
    {
      constexpr double kFrequency_Hz = 5.0;
      constexpr double kAmplitude_m = 1e-3;
      const double w = 2.0 * 3.14159265358979323846 * kFrequency_Hz;
      const auto ticks = static_cast<int>(std::lround(2.0 * rate_hz));
      const int from = ticks / 2;
      VelocityState state;
      double in_phase = 0.0;
      double quadrature = 0.0;
      for (int k = 0; k < ticks; ++k) {
        const double t_s = k * period_s;
        const double v_m_per_s = estimate_velocity(config, rate_hz, kAmplitude_m * std::sin(w * t_s), &state);
        if (k >= from) {
          in_phase += v_m_per_s * std::cos(w * t_s);
          quadrature += v_m_per_s * std::sin(w * t_s);
        }
      }
      const double n = ticks - from;
      q.delay_ticks = std::atan2(quadrature, in_phase) / (w * period_s);
      q.gain = 2.0 / n * std::hypot(in_phase, quadrature) / (kAmplitude_m * w);
    }
    qualities.push_back(q);
  }
  return qualities;
}

}  // namespace hapscene
