#include "engine/bench/accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

namespace hapscene {
namespace {

constexpr double kReleaseSpring_N_per_m = 100.0;   // the lab spring
constexpr double kReleaseStart_m = 0.004;
constexpr double kReleaseDuration_s = 1.0;
constexpr double kWall_N_per_m = 500.0;            // the lab wall
constexpr double kWall_m = 0.01;
constexpr double kWallSpeed_m_per_s = 0.1;
constexpr double kWallDepth_m = 0.01;              // the hand's reference goes this far in
constexpr double kHandStiffness_N_per_m = 2000.0;  // stiff: the handle keeps the hand's speed
constexpr double kHandDamping_N_s_per_m = 10.0;
constexpr double kReferenceRate_Hz = 100000.0;
constexpr double kFineStep_s = 1e-6;               // the fine integrator's step

// A simulated trajectory at the ticks: the true position and the force held after it.
struct Trajectory {
  double period_s{};
  std::vector<double> x_m;
  std::vector<double> force_N;
  bool finite{true};
};

double duration_of(AccuracyScenario scenario) {
  return scenario == AccuracyScenario::release
             ? kReleaseDuration_s
             : 2.0 * (kWall_m + kWallDepth_m) / kWallSpeed_m_per_s + 0.2;
}

// The plant for a scenario: the profile's mass and damping; no Coulomb friction for the
// release (its truth is the linear oscillator), no sensor noise.
DeviceProfile scenario_profile(const DeviceProfile& profile, AccuracyScenario scenario) {
  DeviceProfile p = profile;
  p.plant.sensor_noise_counts = 0.0;
  if (scenario == AccuracyScenario::release) p.plant.coulomb_N = 0.0;
  return p;
}

SimulationConfig scenario_config(AccuracyScenario scenario, PlantIntegrator integrator, int substeps) {
  SimulationConfig config;
  config.integrator = integrator;
  config.substeps_per_tick = substeps;
  if (scenario == AccuracyScenario::release) {
    config.start_x_m = kReleaseStart_m;
    config.hand.motion = HandMotion::none;
  } else {
    // In to the wall and through to kWallDepth_m beyond it at a fixed speed, a short
    // hold, back out at the same speed, a short rest.
    const double in_s = (kWall_m + kWallDepth_m) / kWallSpeed_m_per_s;
    config.hand.motion = HandMotion::path;
    config.hand.stiffness_N_per_m = kHandStiffness_N_per_m;
    config.hand.damping_N_s_per_m = kHandDamping_N_s_per_m;
    config.hand.path = {{0.0, 0.0, true},
                        {in_s, kWall_m + kWallDepth_m, true},
                        {in_s + 0.1, kWall_m + kWallDepth_m, true},
                        {2.0 * in_s + 0.1, 0.0, true},
                        {2.0 * in_s + 0.2, 0.0, true}};
  }
  return config;
}

double rendered_force_N(AccuracyScenario scenario, double x_m) {
  if (scenario == AccuracyScenario::release) return -kReleaseSpring_N_per_m * x_m;
  return x_m > kWall_m ? -kWall_N_per_m * (x_m - kWall_m) : 0.0;
}

// The loop with an ideal sensor and motor: force from the true position, held one tick.
void simulate(const DeviceProfile& profile, AccuracyScenario scenario, double rate_hz,
              PlantIntegrator integrator, int substeps, Trajectory* out) {
  HapkitPlant plant(profile, scenario_config(scenario, integrator, substeps));
  const auto ticks = static_cast<std::size_t>(std::llround(duration_of(scenario) * rate_hz));
  const double period_s = 1.0 / rate_hz;
  const double h_s = period_s / substeps;
  out->period_s = period_s;
  out->x_m.resize(ticks);
  out->force_N.resize(ticks);
  for (std::size_t k = 0; k < ticks; ++k) {
    const double x_m = plant.x_m();
    const double force_N = rendered_force_N(scenario, x_m);
    out->x_m[k] = x_m;
    out->force_N[k] = force_N;
    for (int i = 0; i < substeps; ++i) plant.substep(h_s, force_N);
  }
  out->finite = std::all_of(out->x_m.begin(), out->x_m.end(), [](double x) { return std::isfinite(x); });
}

// The same, timed: the best CPU time per simulated second over enough repeats.
double timed_simulate(const DeviceProfile& profile, const AccuracyCase& c, Trajectory* out) {
  using Clock = std::chrono::steady_clock;
  double best_s = INFINITY;
  double total_s = 0.0;
  for (int repeat = 0; repeat < 20 && (repeat < 3 || total_s < kAccuracyMinTimedRun_s); ++repeat) {
    const auto begin = Clock::now();
    simulate(profile, c.scenario, c.rate_hz, c.integrator, c.substeps, out);
    const double run_s = std::chrono::duration<double>(Clock::now() - begin).count();
    best_s = std::min(best_s, run_s);
    total_s += run_s;
  }
  return best_s / duration_of(c.scenario);
}

// The fine run at a given loop rate: RK4 at steps of at most 1 us.
void fine_simulate(const DeviceProfile& profile, AccuracyScenario scenario, double rate_hz, Trajectory* out) {
  const int substeps = std::max(1, static_cast<int>(std::ceil(1.0 / (rate_hz * kFineStep_s) - 1e-9)));
  simulate(profile, scenario, rate_hz, PlantIntegrator::rk4, substeps, out);
}

double rms(double sum_squares, std::size_t count) {
  return count == 0 ? 0.0 : std::sqrt(sum_squares / static_cast<double>(count));
}

// Position RMS of `a` against `b` at a's ticks, b sampled `ratio` times as often.
double position_rms_m(const Trajectory& a, const Trajectory& b, std::size_t ratio) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < a.x_m.size() && k * ratio < b.x_m.size(); ++k, ++n) {
    const double d = a.x_m[k] - b.x_m[k * ratio];
    sum += d * d;
  }
  return rms(sum, n);
}

// The release's analytic motion: x0 e^(-s t) (cos wd t + s / wd sin wd t).
struct Oscillator {
  double sigma{};
  double omega_d{};
  double x0{};
  double at(double t_s) const {
    return x0 * std::exp(-sigma * t_s) * (std::cos(omega_d * t_s) + sigma / omega_d * std::sin(omega_d * t_s));
  }
};

Oscillator release_truth(const DeviceProfile& profile) {
  const double m = profile.plant.mass_kg;
  const double sigma = profile.plant.viscous_N_s_per_m / (2.0 * m);
  return {sigma, std::sqrt(kReleaseSpring_N_per_m / m - sigma * sigma), kReleaseStart_m};
}

// Frequency from the zero crossings (linear interpolation between ticks) and decay rate
// from a least-squares line through the log of each half-cycle's peak (parabolic
// interpolation around the largest sample).
void measure_release(const Trajectory& tr, double* frequency_Hz, double* decay_per_s) {
  const std::vector<double>& x = tr.x_m;
  const double T = tr.period_s;
  std::vector<double> crossings;
  for (std::size_t k = 1; k < x.size(); ++k) {
    if ((x[k - 1] > 0.0) != (x[k] > 0.0)) crossings.push_back(T * (static_cast<double>(k - 1) + x[k - 1] / (x[k - 1] - x[k])));
  }
  *frequency_Hz = crossings.size() >= 2
                      ? static_cast<double>(crossings.size() - 1) / (2.0 * (crossings.back() - crossings.front()))
                      : NAN;
  // Peaks between consecutive crossings (and before the first).
  double sum_t = 0.0, sum_y = 0.0, sum_tt = 0.0, sum_ty = 0.0;
  int n = 0;
  std::size_t begin = 1;
  for (std::size_t c = 0; c <= crossings.size(); ++c) {
    const std::size_t end = c < crossings.size() ? static_cast<std::size_t>(crossings[c] / T) : x.size() - 1;
    std::size_t best = begin;
    for (std::size_t k = begin; k < end && k + 1 < x.size(); ++k) {
      if (std::abs(x[k]) > std::abs(x[best])) best = k;
    }
    if (best >= 1 && best + 1 < x.size() && best > begin && best + 1 < end &&
        std::abs(x[best]) > 1e-3 * kReleaseStart_m) {
      const double a = std::abs(x[best - 1]), b = std::abs(x[best]), d = std::abs(x[best + 1]);
      const double curvature = a - 2.0 * b + d;
      const double offset = curvature != 0.0 ? 0.5 * (a - d) / curvature : 0.0;
      const double peak = b - 0.25 * (a - d) * offset;
      const double t = (static_cast<double>(best) + offset) * T;
      sum_t += t;
      sum_y += std::log(peak);
      sum_tt += t * t;
      sum_ty += t * std::log(peak);
      ++n;
    }
    begin = end + 1;
  }
  const double denominator = n * sum_tt - sum_t * sum_t;
  *decay_per_s = n >= 2 && denominator > 0.0 ? -(n * sum_ty - sum_t * sum_y) / denominator : NAN;
}

}  // namespace

AccuracySetup accuracy_setup(const DeviceProfile& profile) {
  const Oscillator o = release_truth(profile);
  return AccuracySetup{profile.plant.mass_kg,
                       profile.plant.viscous_N_s_per_m,
                       kReleaseSpring_N_per_m,
                       kReleaseStart_m,
                       o.omega_d / (2.0 * std::numbers::pi),
                       o.sigma,
                       kWall_N_per_m,
                       kWall_m,
                       kWallSpeed_m_per_s,
                       kHandStiffness_N_per_m,
                       kHandDamping_N_s_per_m};
}

std::vector<AccuracyCase> default_accuracy_cases() {
  std::vector<AccuracyCase> cases;
  for (const AccuracyScenario scenario : {AccuracyScenario::release, AccuracyScenario::wall}) {
    for (const double rate_hz : {250.0, 500.0, 1000.0, 2000.0, 5000.0, 10000.0, 20000.0}) {
      for (const PlantIntegrator integrator :
           {PlantIntegrator::semi_implicit_euler, PlantIntegrator::rk4, PlantIntegrator::exact}) {
        for (const int substeps : {1, 2, 5, 10, 20}) cases.push_back({scenario, rate_hz, integrator, substeps});
      }
    }
  }
  return cases;
}

namespace {

// True when some other comparable result is no slower and no less accurate, and better in one.
template <typename Comparable, typename Error>
bool dominated(const AccuracyResult& r, const std::vector<AccuracyResult>& all, Comparable comparable, Error error) {
  for (const AccuracyResult& other : all) {
    if (&other == &r || !other.finite || !comparable(other)) continue;
    const bool no_worse = other.run_time_s_per_s <= r.run_time_s_per_s && error(other) <= error(r);
    const bool better = other.run_time_s_per_s < r.run_time_s_per_s || error(other) < error(r);
    if (no_worse && better) return true;
  }
  return false;
}

}  // namespace

void mark_pareto_fronts(std::vector<AccuracyResult>* results) {
  for (AccuracyResult& r : *results) {
    const auto same_scenario = [&](const AccuracyResult& o) { return o.which.scenario == r.which.scenario; };
    const auto same_rate = [&](const AccuracyResult& o) {
      return o.which.scenario == r.which.scenario && o.which.rate_hz == r.which.rate_hz;
    };
    r.front_truth = r.finite && !dominated(r, *results, same_scenario,
                                           [](const AccuracyResult& o) { return o.position_rms_m; });
    r.front_integration = r.finite && !dominated(r, *results, same_rate,
                                                 [](const AccuracyResult& o) { return o.integration_rms_m; });
  }
}

std::vector<AccuracyResult> run_accuracy_sweep(const DeviceProfile& profile,
                                               const std::vector<AccuracyCase>& cases) {
  const Oscillator truth = release_truth(profile);
  const DeviceProfile release_profile = scenario_profile(profile, AccuracyScenario::release);
  const DeviceProfile wall_profile = scenario_profile(profile, AccuracyScenario::wall);

  // The wall's truth: a 100 kHz loop with 1 us RK4 steps, computed once.
  Trajectory wall_truth;
  const bool any_wall = std::any_of(cases.begin(), cases.end(),
                                    [](const AccuracyCase& c) { return c.scenario == AccuracyScenario::wall; });
  if (any_wall) fine_simulate(wall_profile, AccuracyScenario::wall, kReferenceRate_Hz, &wall_truth);

  std::vector<AccuracyResult> results;
  Trajectory run, fine;
  for (const AccuracyCase& c : cases) {
    const DeviceProfile& p = c.scenario == AccuracyScenario::release ? release_profile : wall_profile;
    AccuracyResult r;
    r.which = c;
    r.run_time_s_per_s = timed_simulate(p, c, &run);
    r.finite = run.finite;
    fine_simulate(p, c.scenario, c.rate_hz, &fine);
    r.integration_rms_m = position_rms_m(run, fine, 1);
    const double T = run.period_s;

    if (c.scenario == AccuracyScenario::release) {
      // Against the continuous oscillator: at the ticks, and the held force on a fine grid.
      double sum_x = 0.0, sum_f = 0.0;
      constexpr int kPerTick = 10;
      for (std::size_t k = 0; k < run.x_m.size(); ++k) {
        const double d = run.x_m[k] - truth.at(T * static_cast<double>(k));
        sum_x += d * d;
        for (int j = 0; j < kPerTick; ++j) {
          const double f = run.force_N[k] + kReleaseSpring_N_per_m * truth.at(T * (static_cast<double>(k) + j / double(kPerTick)));
          sum_f += f * f;
        }
      }
      r.position_rms_m = rms(sum_x, run.x_m.size());
      r.force_rms_N = rms(sum_f, run.x_m.size() * kPerTick);
      double frequency_Hz = NAN, decay_per_s = NAN;
      measure_release(run, &frequency_Hz, &decay_per_s);
      const double analytic_Hz = truth.omega_d / (2.0 * std::numbers::pi);
      r.frequency_error = (frequency_Hz - analytic_Hz) / analytic_Hz;
      r.decay_error = (decay_per_s - truth.sigma) / truth.sigma;
    } else {
      // Against the 100 kHz truth: positions at the ticks, held forces on its grid.
      const auto ratio = static_cast<std::size_t>(std::llround(kReferenceRate_Hz / c.rate_hz));
      r.position_rms_m = position_rms_m(run, wall_truth, ratio);
      double sum_f = 0.0;
      std::size_t n = 0;
      for (std::size_t j = 0; j < wall_truth.force_N.size() && j / ratio < run.force_N.size(); ++j, ++n) {
        const double f = run.force_N[j / ratio] - wall_truth.force_N[j];
        sum_f += f * f;
      }
      r.force_rms_N = rms(sum_f, n);
      r.frequency_error = NAN;
      r.decay_error = NAN;
    }
    if (!std::isfinite(r.position_rms_m)) r.finite = false;
    results.push_back(r);
  }
  mark_pareto_fronts(&results);
  return results;
}

}  // namespace hapscene
