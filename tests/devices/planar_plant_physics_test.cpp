// The planar plant's physics over time, both families: energy is kept without friction and
// lost with it, end stops stop the joints, torque limits clamp, Coulomb friction sticks and
// breaks away, the sensor quantizes (and wraps), and runs are deterministic.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "engine/devices/planar/planar_plant.hpp"
#include "engine/devices/planar/planar_plant_examples.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {

constexpr double kTick_s = 1e-3;

// The example with every loss and force switched off.
PlanarPlantParameters lossless(PlanarPlantParameters p) {
  p.viscous_N_m_s_per_rad = Vec2{};
  p.coulomb_N_m = Vec2{};
  p.stop_damping_N_m_s_per_rad = Vec2{};
  return p;
}

PlanarSimulationConfig moving_from(const Vec2& q, const Vec2& q_dot) {
  PlanarSimulationConfig config;
  config.start_q_rad = q;
  config.start_q_dot_rad_per_s = q_dot;
  return config;
}

struct EnergyRun {
  double initial_J{};
  double worst_relative_drift{};    // of kinetic + stop energy
  double worst_free_relative{};     // kinetic energy whenever no stop is touched
  int stop_contacts{};              // ticks in contact
};

// 10 s at 1 kHz with the default integrator, no motor, no hand.
EnergyRun run_energy(const PlanarPlantParameters& p, const PlanarSimulationConfig& config) {
  PlanarPlant plant(p, config);
  EnergyRun r;
  r.initial_J = plant.kinetic_energy_J() + plant.stop_energy_J();
  for (int k = 0; k < 10000; ++k) {
    plant.advance(kTick_s);
    const double kinetic = plant.kinetic_energy_J(), stops = plant.stop_energy_J();
    r.worst_relative_drift = std::max(r.worst_relative_drift, std::abs(kinetic + stops - r.initial_J) / r.initial_J);
    if (stops == 0.0) r.worst_free_relative = std::max(r.worst_free_relative, std::abs(kinetic - r.initial_J) / r.initial_J);
    else ++r.stop_contacts;
  }
  CHECK(plant.linkage_faults() == 0);
  return r;
}

}  // namespace

TEST_CASE("planar plant: without friction, motor or hand the kinetic energy stays constant for 10 s (serial 2R, spinning)") {
  // No stops: the arm spins freely, the Coriolis and centrifugal terms working all the time.
  PlanarPlantParameters p = lossless(example_haplink_plant().parameters);
  p.stop_min_rad = Vec2{{-kNoLimit, -kNoLimit}};
  p.stop_max_rad = Vec2{{kNoLimit, kNoLimit}};
  const EnergyRun r = run_energy(p, moving_from(Vec2{}, Vec2{{3.0, -7.0}}));
  MESSAGE("serial 2R free spin: kinetic energy ", r.initial_J, " J, worst relative drift ", r.worst_relative_drift);
  CHECK(r.stop_contacts == 0);
  CHECK(r.worst_relative_drift < 1e-9);
}

TEST_CASE("planar plant: without friction, motor or hand the energy stays constant for 10 s (five-bar, elastic stops)") {
  // The five-bar cannot spin: elastic stops (no damping) turn it back, and kinetic plus stop
  // energy is kept; between contacts the kinetic energy is the initial one.
  const PlanarPlantExample example = example_haply2diy_v3_plant();
  const EnergyRun r = run_energy(lossless(example.parameters), moving_from(example.home_q_rad, Vec2{{2.0, -1.5}}));
  MESSAGE("five-bar with elastic stops: energy ", r.initial_J, " J, worst relative drift ", r.worst_relative_drift,
          ", kinetic between contacts ", r.worst_free_relative, ", ticks in contact ", r.stop_contacts);
  CHECK(r.stop_contacts > 100);
  CHECK(r.worst_relative_drift < 5e-4);
  CHECK(r.worst_free_relative < 5e-4);
}

TEST_CASE("planar plant: the serial arm's energy between elastic stop contacts stays constant too") {
  const PlanarPlantExample example = example_haplink_plant();
  const EnergyRun r = run_energy(lossless(example.parameters), moving_from(example.home_q_rad, Vec2{{4.0, -3.0}}));
  MESSAGE("serial 2R with elastic stops: worst relative drift ", r.worst_relative_drift, ", kinetic between contacts ",
          r.worst_free_relative, ", ticks in contact ", r.stop_contacts);
  CHECK(r.stop_contacts > 100);
  CHECK(r.worst_relative_drift < 5e-4);
  CHECK(r.worst_free_relative < 5e-4);
}

TEST_CASE("planar plant: viscous friction makes the energy decay") {
  for (const PlanarPlantExample& example : {example_haplink_plant(), example_haply2diy_v3_plant()}) {
    PlanarPlantParameters p = lossless(example.parameters);
    p.viscous_N_m_s_per_rad = Vec2{{5e-3, 5e-3}};
    PlanarPlant plant(p, moving_from(example.home_q_rad, Vec2{{1.0, -1.0}}));
    const double start_J = plant.kinetic_energy_J();
    double previous_J = start_J + plant.stop_energy_J();
    bool never_grew = true;
    for (int k = 0; k < 2000; ++k) {
      plant.advance(kTick_s);
      const double now_J = plant.kinetic_energy_J() + plant.stop_energy_J();
      never_grew = never_grew && now_J <= previous_J * (1.0 + 1e-9);
      previous_J = now_J;
    }
    CHECK(never_grew);
    CHECK(previous_J < 0.01 * start_J);
  }
}

TEST_CASE("planar plant: end stops stop the joints against a steady motor torque") {
  for (const PlanarPlantExample& example : {example_haplink_plant(), example_haply2diy_v3_plant()}) {
    const PlanarPlantParameters& p = example.parameters;
    PlanarSimulationConfig config;
    config.start_q_rad = example.home_q_rad;
    PlanarPlant plant(p, config);
    // Full torque on joint 1 toward its upper stop and on joint 2 toward its lower stop.
    const Vec2 joint_push{{0.1, -0.1}};
    plant.hold_motor_torques(motor_torques_for_joint_torques(p, joint_push));
    for (int k = 0; k < 3000; ++k) plant.advance(kTick_s);
    const Vec2 applied = plant.joint_torque_N_m();
    const Vec2 q = plant.q_rad();
    // At rest on the stops, pressed in by torque / stiffness (plus what the other joint's
    // stop adds through the coupling: a generous factor of two).
    CHECK(std::abs(plant.q_dot_rad_per_s()[0]) < 1e-3);
    CHECK(std::abs(plant.q_dot_rad_per_s()[1]) < 1e-3);
    CHECK(q[0] > p.stop_max_rad[0]);
    CHECK(q[0] - p.stop_max_rad[0] < 2.0 * std::abs(applied[0]) / p.stop_stiffness_N_m_per_rad[0] + 1e-3);
    CHECK(q[1] < p.stop_min_rad[1]);
    CHECK(p.stop_min_rad[1] - q[1] < 2.0 * std::abs(applied[1]) / p.stop_stiffness_N_m_per_rad[1] + 1e-3);
    CHECK(plant.linkage_faults() == 0);
  }
}

TEST_CASE("planar plant: motor torque limits clamp each motor and are counted") {
  const PlanarPlantExample example = example_haply2diy_v3_plant();
  PlanarSimulationConfig config;
  config.start_q_rad = example.home_q_rad;
  PlanarPlant plant(example.parameters, config);
  plant.hold_motor_torques(Vec2{{0.05, -0.01}});
  CHECK(plant.motor_torque_N_m() == Vec2{{0.05, -0.01}});
  CHECK(plant.saturations() == 0);
  plant.hold_motor_torques(Vec2{{1.0, -5.0}});
  CHECK(plant.motor_torque_N_m() == Vec2{{0.123, -0.123}});
  CHECK(plant.saturations() == 1);
  plant.hold_motor_torques(Vec2{{NAN, 0.01}});
  CHECK(plant.motor_torque_N_m() == Vec2{{0.0, 0.01}});
  CHECK(plant.command_faults() == 1);

  // Through the Haplink's capstan the joint sees the clamped motor torque times -72/5.5.
  const PlanarPlantExample haplink = example_haplink_plant();
  PlanarSimulationConfig at_home;
  PlanarPlant arm(haplink.parameters, at_home);
  arm.hold_motor_torques(Vec2{{1.0, -1.0}});
  CHECK(arm.joint_torque_N_m()[0] == doctest::Approx(-72.0 / 5.5 / 65.13));
  CHECK(arm.joint_torque_N_m()[1] == doctest::Approx(72.0 / 5.5 / 65.13));
}

TEST_CASE("planar plant: Coulomb friction holds a joint below its level and lets it go above") {
  const PlanarPlantExample example = example_haply2diy_v3_plant();
  PlanarPlantParameters p = example.parameters;
  p.coulomb_N_m = Vec2{{0.01, 0.01}};
  PlanarSimulationConfig config;
  config.start_q_rad = example.home_q_rad;
  {
    PlanarPlant plant(p, config);
    plant.hold_motor_torques(Vec2{{0.009, -0.009}});
    for (int k = 0; k < 500; ++k) plant.advance(kTick_s);
    CHECK(plant.q_rad() == example.home_q_rad);
    CHECK(plant.q_dot_rad_per_s() == Vec2{});
  }
  {
    // Only joint 1 pushed past its level: joint 1 moves; joint 2 is dragged only if the
    // coupling beats its friction, and it never moves the wrong way first.
    PlanarPlant plant(p, config);
    plant.hold_motor_torques(Vec2{{0.02, 0.0}});
    for (int k = 0; k < 100; ++k) plant.advance(kTick_s);
    CHECK(plant.q_rad()[0] > example.home_q_rad[0] + 0.01);
  }
  {
    // A joint coasting against friction comes to rest and stays there (no creeping back
    // and forth): velocity exactly zero.
    PlanarPlant plant(p, moving_from(example.home_q_rad, Vec2{{1.0, -1.0}}));
    for (int k = 0; k < 1000; ++k) plant.advance(kTick_s);
    CHECK(plant.q_dot_rad_per_s() == Vec2{});
    const Vec2 rest = plant.q_rad();
    for (int k = 0; k < 100; ++k) plant.advance(kTick_s);
    CHECK(plant.q_rad() == rest);
  }
}

TEST_CASE("planar plant: the sensor reports motor angles in counts, wrapped for an MR-style sensor") {
  const PlanarPlantExample example = example_haplink_plant();
  PlanarPlantParameters p = example.parameters;
  PlanarSimulationConfig config;
  config.start_q_rad = Vec2{{0.1, -0.2}};
  {
    PlanarPlant plant(p, config);
    // Motor angle = T^T q = -72/5.5 q; 48 counts per motor turn; nearest count.
    const auto counts = plant.sensor_counts();
    CHECK(counts[0] == static_cast<int>(std::nearbyint(-72.0 / 5.5 * 0.1 / (2 * std::numbers::pi / 48))));
    CHECK(counts[1] == static_cast<int>(std::nearbyint(-72.0 / 5.5 * -0.2 / (2 * std::numbers::pi / 48))));
    CHECK(counts[0] == -10);
    CHECK(counts[1] == 20);
  }
  {
    p.sensor_period_counts = {16, 16};
    p.sensor_min_counts = {0, 3};
    PlanarPlant plant(p, config);
    const auto counts = plant.sensor_counts();
    CHECK(counts[0] == 6);      // -10 mod 16
    CHECK(counts[1] == 4);      // 3 + (20 - 3) mod 16
  }
  {
    // Noise is seeded: the same seed gives the same readings, another seed others.
    p.sensor_noise_counts = 3.0;
    PlanarPlant a(p, config), b(p, config);
    config.noise_seed = 2;
    PlanarPlant c(p, config);
    bool differs = false;
    for (int k = 0; k < 20; ++k) {
      const auto ra = a.sensor_counts(), rb = b.sensor_counts(), rc = c.sensor_counts();
      CHECK(ra == rb);
      differs = differs || ra != rc;
    }
    CHECK(differs);
  }
}

TEST_CASE("planar plant: runs are deterministic to the bit") {
  const PlanarPlantExample example = example_haply2diy_v3_plant();
  PlanarSimulationConfig config;
  config.start_q_rad = example.home_q_rad;
  config.hand.motion = PlanarHandMotion::circle;
  config.hand.circle_center_m = Vec2{{0.019, 0.12}};
  config.hand.circle_radius_m = 0.02;
  config.hand.speed_m_per_s = 0.1;
  PlanarPlant a(example.parameters, config), b(example.parameters, config);
  for (int k = 0; k < 2000; ++k) {
    const Vec2 torque{{0.02 * std::sin(k * 0.01), -0.01}};
    a.hold_motor_torques(torque);
    b.hold_motor_torques(torque);
    a.advance(kTick_s);
    b.advance(kTick_s);
  }
  CHECK(a.q_rad() == b.q_rad());
  CHECK(a.q_dot_rad_per_s() == b.q_dot_rad_per_s());
  CHECK(a.t_s() == b.t_s());
}

}  // namespace HAPSCENE_TEST_FILE
