#include "engine/bench/planar_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>

#include "engine/bench/accuracy.hpp"
#include "engine/devices/planar/simulated_planar.hpp"

namespace hapscene {
namespace {

constexpr double kSpring_N_per_m = 200.0;
const Vec2 kReleaseOffset_m{{0.008, -0.005}};
constexpr double kCircleRadius_m = 0.015;
constexpr double kHandSpeed_m_per_s = 0.1;
constexpr double kPlanarWall_N_per_m = 1000.0;
constexpr double kWallDistance_m = 0.01;
constexpr double kPlanarWallDepth_m = 0.01;

double duration_of(PlanarAccuracyScenario scenario) {
  switch (scenario) {
    case PlanarAccuracyScenario::release: return 1.0;
    case PlanarAccuracyScenario::circle: return 1.5;
    case PlanarAccuracyScenario::wall: return 2.0 * (kWallDistance_m + kPlanarWallDepth_m) / kHandSpeed_m_per_s + 0.2;
  }
  return 1.0;
}

// The wall's direction from home (into it) and its unit normal (out of the solid).
Vec2 wall_direction() { return Vec2{{1.0, 1.0}} / std::sqrt(2.0); }

struct Setup {
  PlanarPlantParameters parameters;
  PlanarSimulationConfig config;
  Vec2 home_m{};
};

Setup scenario_setup(const PlanarPlantExample& device, PlanarAccuracyScenario scenario, PlanarIntegrator integrator,
                     int substeps) {
  Setup s;
  s.parameters = device.parameters;
  s.parameters.sensor_noise_counts = 0.0;
  s.config.start_q_rad = device.home_q_rad;
  s.config.integrator = integrator;
  s.config.substeps_per_tick = substeps;
  s.home_m = solve_linkage(device.parameters.linkage, device.home_q_rad).handle_m;
  PlanarHandConfig& hand = s.config.hand;
  switch (scenario) {
    case PlanarAccuracyScenario::release: {
      s.parameters.coulomb_N_m = Vec2{};
      Vec2 q{};
      if (joint_angles_for_handle(device.parameters.linkage, s.home_m + kReleaseOffset_m, device.home_q_rad, &q)) {
        s.config.start_q_rad = q;
      }
      hand.motion = PlanarHandMotion::none;
      break;
    }
    case PlanarAccuracyScenario::circle:
      hand.motion = PlanarHandMotion::circle;
      hand.stiffness_N_per_m = 500.0;
      hand.damping_N_s_per_m = 5.0;
      hand.speed_m_per_s = kHandSpeed_m_per_s;
      hand.circle_center_m = s.home_m;
      hand.circle_radius_m = kCircleRadius_m;
      break;
    case PlanarAccuracyScenario::wall: {
      const double in_s = (kWallDistance_m + kPlanarWallDepth_m) / kHandSpeed_m_per_s;
      const Vec2 deep = s.home_m + (kWallDistance_m + kPlanarWallDepth_m) * wall_direction();
      hand.motion = PlanarHandMotion::path;
      hand.stiffness_N_per_m = 2000.0;
      hand.damping_N_s_per_m = 10.0;
      hand.path = {{0.0, s.home_m, true},
                   {in_s, deep, true},
                   {in_s + 0.1, deep, true},
                   {2.0 * in_s + 0.1, s.home_m, true},
                   {2.0 * in_s + 0.2, s.home_m, true}};
      break;
    }
  }
  return s;
}

Vec2 rendered_force_N(PlanarAccuracyScenario scenario, const Vec2& home_m, const Vec2& p_m) {
  switch (scenario) {
    case PlanarAccuracyScenario::release: return -kSpring_N_per_m * (p_m - home_m);
    case PlanarAccuracyScenario::circle: return Vec2{};
    case PlanarAccuracyScenario::wall: {
      const Vec2 normal = -wall_direction();
      const double depth = dot(home_m + kWallDistance_m * wall_direction() - p_m, normal);
      return depth > 0.0 ? kPlanarWall_N_per_m * depth * normal : Vec2{};
    }
  }
  return Vec2{};
}

struct PlanarTrajectory {
  std::vector<Vec2> handle_m;
  bool finite{true};
};

// The loop with an ideal sensor and drive: the force from the true handle position, J^T F
// at that pose, held for the tick.
void simulate(const PlanarPlantExample& device, PlanarAccuracyScenario scenario, double rate_hz,
              PlanarIntegrator integrator, int substeps, PlanarTrajectory* out) {
  const Setup s = scenario_setup(device, scenario, integrator, substeps);
  PlanarPlant plant(s.parameters, s.config);
  const auto ticks = static_cast<std::size_t>(std::llround(duration_of(scenario) * rate_hz));
  const double period_s = 1.0 / rate_hz;
  out->handle_m.resize(ticks);
  for (std::size_t k = 0; k < ticks; ++k) {
    const Vec2 p = plant.handle_m();
    out->handle_m[k] = p;
    const Vec2 joint = joint_torques_N_m(plant.pose().jacobian, rendered_force_N(scenario, s.home_m, p));
    plant.hold_motor_torques(motor_torques_for_joint_torques(s.parameters, joint));
    plant.advance(period_s);
  }
  out->finite = plant.linkage_faults() == 0 &&
                std::all_of(out->handle_m.begin(), out->handle_m.end(), [](const Vec2& p) { return all_finite(p); });
}

}  // namespace

PlanarPlantExample planar_accuracy_device(const PlanarProfile& profile) {
  return PlanarPlantExample{planar_plant_parameters(profile), planar_joint_angles_at(profile, profile.home_m)};
}

std::vector<PlanarAccuracyCase> default_planar_accuracy_cases() {
  std::vector<PlanarAccuracyCase> cases;
  for (const PlanarAccuracyScenario scenario :
       {PlanarAccuracyScenario::release, PlanarAccuracyScenario::circle, PlanarAccuracyScenario::wall}) {
    for (const double rate_hz : {500.0, 1000.0, 2000.0, 5000.0}) {
      for (const PlanarIntegrator integrator : {PlanarIntegrator::semi_implicit_euler, PlanarIntegrator::rk4}) {
        for (const int substeps : {1, 2, 4, 8}) cases.push_back({scenario, rate_hz, integrator, substeps});
      }
    }
  }
  return cases;
}

std::vector<PlanarAccuracyResult> run_planar_accuracy(const PlanarPlantExample& device,
                                                      const std::vector<PlanarAccuracyCase>& cases,
                                                      const PlanarAccuracyOptions& options) {
  using Clock = std::chrono::steady_clock;
  std::map<std::pair<int, double>, PlanarTrajectory> fine_runs;
  std::vector<PlanarAccuracyResult> results;
  PlanarTrajectory run;
  for (const PlanarAccuracyCase& c : cases) {
    const auto key = std::make_pair(static_cast<int>(c.scenario), c.rate_hz);
    auto fine = fine_runs.find(key);
    if (fine == fine_runs.end()) {
      const int substeps = std::max(1, static_cast<int>(std::ceil(1.0 / (c.rate_hz * options.fine_step_s) - 1e-9)));
      PlanarTrajectory t;
      simulate(device, c.scenario, c.rate_hz, PlanarIntegrator::rk4, substeps, &t);
      fine = fine_runs.emplace(key, std::move(t)).first;
    }
    PlanarAccuracyResult r;
    r.which = c;
    double best_s = INFINITY, total_s = 0.0;
    const int repeats = options.timed ? 20 : 1;
    for (int repeat = 0; repeat < repeats && (repeat < 3 || total_s < kAccuracyMinTimedRun_s); ++repeat) {
      const auto begin = Clock::now();
      simulate(device, c.scenario, c.rate_hz, c.integrator, c.substeps, &run);
      const double run_s = std::chrono::duration<double>(Clock::now() - begin).count();
      best_s = std::min(best_s, run_s);
      total_s += run_s;
    }
    r.run_time_s_per_s = options.timed ? best_s / duration_of(c.scenario) : NAN;
    r.finite = run.finite && fine->second.finite;
    const std::vector<Vec2>& a = run.handle_m;
    const std::vector<Vec2>& b = fine->second.handle_m;
    double sum = 0.0;
    const std::size_t n = std::min(a.size(), b.size());
    for (std::size_t k = 0; k < n; ++k) {
      const double d = norm(a[k] - b[k]);
      sum += d * d;
      r.integration_max_m = std::max(r.integration_max_m, d);
      if (k > 0) r.travel_m += norm(b[k] - b[k - 1]);
    }
    r.integration_rms_m = n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
    if (!std::isfinite(r.integration_rms_m)) r.finite = false;
    results.push_back(r);
  }
  return results;
}

}  // namespace hapscene
