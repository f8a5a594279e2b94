// The plant's integrators against closed-form answers, their orders of accuracy, and
// Coulomb friction treated the same way by all three.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/bench/accuracy.hpp"
#include "engine/devices/hapkit_plant.hpp"
#include "engine/devices/plant_integrators.hpp"

using namespace hapscene;

namespace {

// x(t) of m x'' + c x' + k x = 0 from (x0, 0), underdamped.
double underdamped_m(double m, double c, double k, double x0, double t) {
  const double s = c / (2 * m);
  const double wd = std::sqrt(k / m - s * s);
  return x0 * std::exp(-s * t) * (std::cos(wd * t) + s / wd * std::sin(wd * t));
}

// A plant held by the hand's spring-damper at 0 (no Coulomb friction, no stops in reach):
// a linear mass-spring-damper whose free motion from x0 is known.
HapkitPlant held_plant(PlantIntegrator integrator, int substeps, double coulomb_N = 0.0) {
  DeviceProfile profile = load_device_profile("hapkit3", ".");
  profile.plant.coulomb_N = coulomb_N;
  SimulationConfig config;
  config.integrator = integrator;
  config.substeps_per_tick = substeps;
  config.start_x_m = 0.004;
  config.hand.motion = HandMotion::hold;
  config.hand.hold_m = 0.0;
  config.hand.stiffness_N_per_m = 200.0;
  config.hand.damping_N_s_per_m = 0.6;
  return HapkitPlant(profile, config);
}

// Largest |x - analytic| over 0.5 s of ticks at 1 kHz.
double max_error_m(PlantIntegrator integrator, int substeps) {
  HapkitPlant plant = held_plant(integrator, substeps);
  const double m = plant.profile().plant.mass_kg;
  const double c = plant.profile().plant.viscous_N_s_per_m + 0.6;
  double worst = 0.0;
  for (int k = 1; k <= 500; ++k) {
    for (int i = 0; i < substeps; ++i) plant.substep(1e-3 / substeps, 0.0);
    worst = std::max(worst, std::abs(plant.x_m() - underdamped_m(m, c, 200.0, 0.004, k * 1e-3)));
  }
  return worst;
}

}  // namespace

TEST_CASE("exact_linear_step: closed forms for under-, over-, critically damped and spring-free motion") {
  const double h = 0.003;
  // Underdamped, from rest at 1 mm.
  double x = 0.001, v = 0.0;
  exact_linear_step({0.04, 0.4, 100.0, 0.0, 0.0}, h, &x, &v);
  CHECK(x == doctest::Approx(underdamped_m(0.04, 0.4, 100.0, 0.001, h)).epsilon(1e-12));
  // Overdamped: x = (l2 e^(l1 t) - l1 e^(l2 t)) / (l2 - l1) x0.
  x = 0.001, v = 0.0;
  exact_linear_step({0.04, 10.0, 100.0, 0.0, 0.0}, h, &x, &v);
  const double mu = -10.0 / 0.08, q = std::sqrt(mu * mu - 100.0 / 0.04);
  const double l1 = mu + q, l2 = mu - q;
  CHECK(x == doctest::Approx(0.001 * (l2 * std::exp(l1 * h) - l1 * std::exp(l2 * h)) / (l2 - l1)).epsilon(1e-12));
  // Critically damped (c^2 = 4 k m): x = x0 (1 + w t) e^(-w t).
  x = 0.001, v = 0.0;
  exact_linear_step({0.04, 2.0 * std::sqrt(100.0 * 0.04), 100.0, 0.0, 0.0}, h, &x, &v);
  CHECK(x == doctest::Approx(0.001 * (1 + 50.0 * h) * std::exp(-50.0 * h)).epsilon(1e-12));
  // Equilibrium under a constant force stays put; a ramp force is followed exactly.
  x = 0.01, v = 0.0;
  exact_linear_step({0.04, 0.4, 100.0, 1.0, 0.0}, h, &x, &v);
  CHECK(x == doctest::Approx(0.01).epsilon(1e-14));
  CHECK(v == doctest::Approx(0.0).scale(1.0).epsilon(1e-12));
  // No spring: v relaxes to F / c; no spring and no damping: constant acceleration.
  x = 0.0, v = 0.0;
  exact_linear_step({0.04, 0.4, 0.0, 0.2, 0.0}, h, &x, &v);
  CHECK(v == doctest::Approx(0.5 * (1 - std::exp(-10.0 * h))).epsilon(1e-12));
  x = 0.0, v = 0.1;
  exact_linear_step({0.04, 0.0, 0.0, 0.2, 0.0}, h, &x, &v);
  CHECK(x == doctest::Approx(0.1 * h + 0.5 * 5.0 * h * h).epsilon(1e-12));
  CHECK(v == doctest::Approx(0.1 + 5.0 * h).epsilon(1e-12));
}

TEST_CASE("plant: exact is exact for a linear plant, RK4 is fourth order, Euler first order") {
  CHECK(max_error_m(PlantIntegrator::exact, 1) < 1e-12);
  const double rk4_1 = max_error_m(PlantIntegrator::rk4, 1);
  const double rk4_2 = max_error_m(PlantIntegrator::rk4, 2);
  CHECK(rk4_1 < 1e-6);
  CHECK(rk4_1 / rk4_2 > 12.0);  // 2^4 = 16 for a fourth-order method
  const double euler_10 = max_error_m(PlantIntegrator::semi_implicit_euler, 10);
  const double euler_20 = max_error_m(PlantIntegrator::semi_implicit_euler, 20);
  CHECK(euler_10 / euler_20 > 1.7);  // 2 for a first-order method
  CHECK(euler_10 / euler_20 < 2.3);
  CHECK(euler_20 > 100.0 * rk4_1);
}

TEST_CASE("plant: Coulomb friction holds a handle below breakaway and lets it go above, for every integrator") {
  for (const PlantIntegrator integrator :
       {PlantIntegrator::semi_implicit_euler, PlantIntegrator::rk4, PlantIntegrator::exact}) {
    CAPTURE(static_cast<int>(integrator));
    DeviceProfile profile = load_device_profile("hapkit3", ".");
    SimulationConfig config;
    config.integrator = integrator;
    config.hand.motion = HandMotion::none;
    HapkitPlant plant(profile, config);
    for (int i = 0; i < 100; ++i) plant.substep(1e-4, 0.9 * profile.plant.coulomb_N);
    CHECK(plant.x_m() == 0.0);
    CHECK(plant.v_m_per_s() == 0.0);
    for (int i = 0; i < 100; ++i) plant.substep(1e-4, 1.5 * profile.plant.coulomb_N);
    CHECK(plant.v_m_per_s() > 0.0);
    // Force removed: friction and damping stop it, and it stays stopped (no creep back).
    for (int i = 0; i < 2000; ++i) plant.substep(1e-4, 0.0);
    const double stopped_m = plant.x_m();
    CHECK(plant.v_m_per_s() == 0.0);
    for (int i = 0; i < 100; ++i) plant.substep(1e-4, 0.0);
    CHECK(plant.x_m() == stopped_m);
  }
}

TEST_CASE("plant: the stiff end stop stays stable with one substep per 4 ms tick for exact") {
  DeviceProfile profile = load_device_profile("hapkit3", ".");
  SimulationConfig config;
  config.integrator = PlantIntegrator::exact;
  config.hand.motion = HandMotion::none;
  HapkitPlant plant(profile, config);
  // Pushed with 3 N against the upper stop (20 N/mm): settles 0.15 mm into it.
  for (int i = 0; i < 500; ++i) plant.substep(4e-3, 3.0);
  CHECK(std::isfinite(plant.x_m()));
  CHECK(plant.x_m() == doctest::Approx(profile.plant.end_stop_max_m + (3.0 - profile.plant.coulomb_N) /
                                                                           profile.plant.end_stop_stiffness_N_per_m)
                           .epsilon(1e-6));
}

TEST_CASE("accuracy: the release's integration error is round-off for exact, and fronts are marked") {
  const DeviceProfile profile = load_device_profile("hapkit3", ".");
  const std::vector<AccuracyResult> results = run_accuracy_sweep(
      profile, {{AccuracyScenario::release, 1000.0, PlantIntegrator::exact, 1},
                {AccuracyScenario::release, 1000.0, PlantIntegrator::semi_implicit_euler, 1}});
  REQUIRE(results.size() == 2);
  CHECK(results[0].integration_rms_m < 1e-9);
  CHECK(results[1].integration_rms_m > 1e-6);
  // The sampled spring loses K T / 2 of damping: the decay is slower than the analytic one.
  CHECK(results[0].decay_error < -0.05);
  CHECK(std::abs(results[0].frequency_error) < 0.01);
  CHECK(results[0].front_integration);

  // A result both slower and less accurate than another is off the front.
  std::vector<AccuracyResult> synthetic(3);
  for (AccuracyResult& r : synthetic) r.which = {AccuracyScenario::wall, 1000.0, PlantIntegrator::rk4, 1};
  synthetic[0].run_time_s_per_s = 1.0, synthetic[0].position_rms_m = 1.0, synthetic[0].integration_rms_m = 1.0;
  synthetic[1].run_time_s_per_s = 2.0, synthetic[1].position_rms_m = 0.5, synthetic[1].integration_rms_m = 2.0;
  synthetic[2].run_time_s_per_s = 3.0, synthetic[2].position_rms_m = 0.7, synthetic[2].integration_rms_m = 0.1;
  mark_pareto_fronts(&synthetic);
  CHECK(synthetic[0].front_truth);
  CHECK(synthetic[1].front_truth);
  CHECK_FALSE(synthetic[2].front_truth);
  CHECK(synthetic[0].front_integration);
  CHECK_FALSE(synthetic[1].front_integration);
  CHECK(synthetic[2].front_integration);
}
