#include "engine/bench/stability_sweep.hpp"

#include <cmath>
#include <cstdio>
#include <functional>

#include "engine/core/velocity.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/harness/validate.hpp"
#include "engine/load/environment.hpp"

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

std::vector<StiffnessLimits> sweep_wall_stiffness(const std::vector<double>& rates_hz) {
  const DeviceProfile profile = stress_profile();
  const HarnessOptions options;  // the harness's hand: 200 N/m, 2 N*s/m, 20 g
  const double b = profile.plant.viscous_N_s_per_m;
  const double count_m = std::abs(counts_to_position_m(profile, 1.0) - counts_to_position_m(profile, 0.0));
  std::vector<StiffnessLimits> limits;
  for (const double rate_hz : rates_hz) {
    // One wall at 10 mm, judged by the press, hold and release scenarios.
    const auto report_for = [&](double k) {
      const Scene scene = load_environment_text(
          R"({"rate_hz": )" + number(rate_hz) + R"(, "effects": [{"type": "wall", "position": 0.01, "stiffness": )" +
              number(k) + R"(, "solid": "above"}]})",
          "stress.json", ".");
      return validate_scene(scene, {ScenarioKind::press, ScenarioKind::hold, ScenarioKind::release}, options);
    };
    StiffnessLimits l;
    l.rate_hz = rate_hz;
    l.bound_2b_over_T = 2.0 * b * rate_hz;
    l.bound_with_hand = 2.0 * (b + options.hand_damping_N_s_per_m) * rate_hz;
    l.bound_coulomb = 2.0 * profile.plant.coulomb_N / count_m;
    l.passive_N_per_m = largest_passing(
        200.0, 1e6, [&](double k) { return first_failure(report_for(k), {"passivity"}).empty(); },
        &l.passive_above_range);
    l.stable_N_per_m = largest_passing(
        200.0, 1e6, [&](double k) { return first_failure(report_for(k), {"limit_cycle", "growth"}).empty(); },
        &l.stable_above_range);
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
