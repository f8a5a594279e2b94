// The planar plant's mass matrix and Coriolis terms against independent computations:
// the kinetic energy from finite differences of the links' positions (solve_linkage only),
// and the Christoffel form of c(q, q_dot) from finite differences of M(q). Both families.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/devices/planar/planar_plant.hpp"
#include "engine/devices/planar/planar_plant_examples.hpp"

using namespace hapscene;

namespace {

// The links' ends at q, in the order of PlanarPlantParameters::links.
struct Ends {
  Vec2 a[4];
  Vec2 b[4];
  Vec2 handle;
  int count{};
};

Ends ends_at(const Linkage& linkage, const Vec2& q) {
  const LinkagePose pose = solve_linkage(linkage, q);
  REQUIRE(pose.valid);
  Ends e;
  e.handle = pose.handle_m;
  if (linkage.family == LinkageFamily::serial_2r) {
    e.a[0] = linkage.serial.base_m, e.b[0] = pose.elbow_1_m;
    e.a[1] = pose.elbow_1_m, e.b[1] = pose.handle_m;
    e.count = 2;
  } else {
    e.a[0] = linkage.five_bar.base_1_m, e.b[0] = pose.elbow_1_m;
    e.a[1] = linkage.five_bar.base_2_m, e.b[1] = pose.elbow_2_m;
    e.a[2] = pose.elbow_1_m, e.b[2] = pose.handle_m;
    e.a[3] = pose.elbow_2_m, e.b[3] = pose.handle_m;
    e.count = 4;
  }
  return e;
}

// Kinetic energy at (q, q_dot) from central differences of positions and link angles along
// q_dot: every link's centre of mass and rotation, the handle, the rotors (T^T q_dot).
double kinetic_energy_by_differences(const PlanarPlantParameters& p, const Vec2& q, const Vec2& q_dot) {
  const double h = 1e-6;
  const Ends up = ends_at(p.linkage, q + h * q_dot);
  const Ends down = ends_at(p.linkage, q - h * q_dot);
  double energy = 0.0;
  for (int i = 0; i < up.count; ++i) {
    const LinkBody& body = p.links[i];
    const double s = body.com_fraction;
    const Vec2 c_up = (1 - s) * up.a[i] + s * up.b[i];
    const Vec2 c_down = (1 - s) * down.a[i] + s * down.b[i];
    const Vec2 v = (c_up - c_down) / (2 * h);
    const Vec2 d_up = up.b[i] - up.a[i], d_down = down.b[i] - down.a[i];
    const double w = std::atan2(cross(d_down, d_up), dot(d_down, d_up)) / (2 * h);
    energy += 0.5 * body.mass_kg * dot(v, v) + 0.5 * body.inertia_kg_m2 * w * w;
  }
  const Vec2 v_handle = (up.handle - down.handle) / (2 * h);
  energy += 0.5 * p.handle_mass_kg * dot(v_handle, v_handle);
  const Matrix2& t = p.motor_to_joint;
  for (int m = 0; m < 2; ++m) {
    const double w = t.m[0][m] * q_dot[0] + t.m[1][m] * q_dot[1];
    energy += 0.5 * p.rotor_inertia_kg_m2[m] * w * w;
  }
  return energy;
}

Matrix2 mass_at(const PlanarMassModel& model, const Vec2& q) {
  PlanarDynamics d;
  REQUIRE(model.evaluate(q, Vec2{}, 0.0, &d));
  return d.mass;
}

// c_i = sum_jk dM_ij/dq_k qd_j qd_k - 1/2 sum_jk dM_jk/dq_i qd_j qd_k, dM/dq by central
// differences.
Vec2 christoffel_bias(const PlanarMassModel& model, const Vec2& q, const Vec2& qd) {
  const double h = 1e-6;
  Matrix2 dm[2];
  for (int k = 0; k < 2; ++k) {
    Vec2 up = q, down = q;
    up[k] += h;
    down[k] -= h;
    const Matrix2 a = mass_at(model, up), b = mass_at(model, down);
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) dm[k].m[i][j] = (a.m[i][j] - b.m[i][j]) / (2 * h);
    }
  }
  Vec2 c{};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 2; ++k) c[i] += dm[k].m[i][j] * qd[j] * qd[k] - 0.5 * dm[i].m[j][k] * qd[j] * qd[k];
    }
  }
  return c;
}

// Poses on a 5 x 5 grid inside the example's stops.
template <typename Check>
void over_grid(const PlanarPlantExample& example, Check check) {
  const PlanarPlantParameters& p = example.parameters;
  for (int a = 0; a < 5; ++a) {
    for (int b = 0; b < 5; ++b) {
      const Vec2 q{{p.stop_min_rad[0] + (p.stop_max_rad[0] - p.stop_min_rad[0]) * (a + 0.5) / 5.0,
                    p.stop_min_rad[1] + (p.stop_max_rad[1] - p.stop_min_rad[1]) * (b + 0.5) / 5.0}};
      check(q);
    }
  }
}

}  // namespace

TEST_CASE("planar plant: M(q) is symmetric, positive definite and gives the links' kinetic energy") {
  for (const PlanarPlantExample& example : {example_haplink_plant(), example_haply2diy_v3_plant()}) {
    const PlanarMassModel model(example.parameters, example.home_q_rad);
    over_grid(example, [&](const Vec2& q) {
      const Matrix2 m = mass_at(model, q);
      CHECK(m.m[0][1] == doctest::Approx(m.m[1][0]).epsilon(1e-12));
      CHECK(m.m[0][0] > 0.0);
      CHECK(m.m[0][0] * m.m[1][1] - m.m[0][1] * m.m[1][0] > 0.0);
      for (const Vec2 qd : {Vec2{{1.0, 0.0}}, Vec2{{0.0, 1.0}}, Vec2{{2.0, -3.0}}}) {
        const double from_model =
            0.5 * (m.m[0][0] * qd[0] * qd[0] + 2 * m.m[0][1] * qd[0] * qd[1] + m.m[1][1] * qd[1] * qd[1]);
        CHECK(from_model == doctest::Approx(kinetic_energy_by_differences(example.parameters, q, qd)).epsilon(1e-6));
      }
    });
  }
}

TEST_CASE("planar plant: the analytic Coriolis terms equal the Christoffel form of dM/dq") {
  for (const PlanarPlantExample& example : {example_haplink_plant(), example_haply2diy_v3_plant()}) {
    const PlanarMassModel model(example.parameters, example.home_q_rad);
    over_grid(example, [&](const Vec2& q) {
      for (const Vec2 qd : {Vec2{{1.0, 0.0}}, Vec2{{0.0, 1.0}}, Vec2{{2.0, -3.0}}, Vec2{{-4.0, -1.0}}}) {
        PlanarDynamics d;
        REQUIRE(model.evaluate(q, qd, 0.0, &d));
        const Vec2 expected = christoffel_bias(model, q, qd);
        const double scale = 1e-6 + norm(expected);
        CHECK(norm(d.bias_N_m - expected) < 1e-5 * scale);
      }
    });
  }
}

TEST_CASE("planar plant: the handle's acceleration at zero joint acceleration is d2p/dt2 along q_dot") {
  // p(q + s q_dot) has second derivative (in s) J_dot q_dot: the bias the plant uses.
  for (const PlanarPlantExample& example : {example_haplink_plant(), example_haply2diy_v3_plant()}) {
    const PlanarMassModel model(example.parameters, example.home_q_rad);
    const Vec2 q = example.home_q_rad, qd{{1.5, -2.0}};
    PlanarDynamics d;
    REQUIRE(model.evaluate(q, qd, 0.0, &d));
    const double h = 1e-4;
    const Vec2 up = solve_linkage(example.parameters.linkage, q + h * qd).handle_m;
    const Vec2 mid = solve_linkage(example.parameters.linkage, q).handle_m;
    const Vec2 down = solve_linkage(example.parameters.linkage, q - h * qd).handle_m;
    const Vec2 second = (up - 2.0 * mid + down) / (h * h);
    CHECK(norm(d.handle_bias_m_per_s2 - second) < 1e-5 * norm(second));
  }
}

TEST_CASE("planar plant: parameters that cannot be simulated are refused with a reason") {
  PlanarPlantExample example = example_haply2diy_v3_plant();
  PlanarSimulationConfig config;
  config.start_q_rad = example.home_q_rad;
  {
    PlanarPlantParameters p = example.parameters;
    p.links[2].mass_kg = -1.0;
    CHECK_THROWS_WITH_AS(PlanarPlant(p, config), doctest::Contains("link 3 mass"), InputError);
  }
  {
    PlanarPlantParameters p = example.parameters;
    p.sensor_step_rad[1] = 0.0;
    CHECK_THROWS_WITH_AS(PlanarPlant(p, config), doctest::Contains("sensor 2 step"), InputError);
  }
  {
    PlanarPlantParameters p = example.parameters;
    for (LinkBody& link : p.links) link = LinkBody{};
    p.handle_mass_kg = 0.0;
    p.rotor_inertia_kg_m2 = Vec2{};
    CHECK_THROWS_WITH_AS(PlanarPlant(p, config), doctest::Contains("singular"), InputError);
  }
  {
    PlanarPlantParameters p = example.parameters;
    p.linkage.five_bar.distal_1_m = p.linkage.five_bar.distal_2_m = 0.03;  // elbows 11 cm apart at home
    CHECK_THROWS_WITH_AS(PlanarPlant(p, config), doctest::Contains("does not close"), InputError);
  }
  {
    PlanarSimulationConfig zero = config;
    zero.substeps_per_tick = 0;
    CHECK_THROWS_WITH_AS(PlanarPlant(example.parameters, zero), doctest::Contains("substeps"), InputError);
  }
}

TEST_CASE("planar plant: a coupled transmission reflects the rotors and reads the sensors through T^T") {
  // The Haplink with its second joint coupled to the first (REFERENCE-2D: a profile
  // parameter): joint torques = T motor torques, motor angles = T^T q.
  PlanarPlantExample example = example_haplink_plant();
  PlanarPlantParameters& p = example.parameters;
  p.motor_to_joint = Matrix2{{{-13.0, 0.0}, {2.0, -13.0}}};
  p.rotor_inertia_kg_m2 = Vec2{{2e-6, 3e-6}};  // large enough to matter
  const PlanarMassModel model(p, example.home_q_rad);
  const Matrix2 m = mass_at(model, example.home_q_rad);
  for (const Vec2 qd : {Vec2{{1.0, 0.0}}, Vec2{{0.0, 1.0}}, Vec2{{2.0, -3.0}}}) {
    const double from_model = 0.5 * (m.m[0][0] * qd[0] * qd[0] + 2 * m.m[0][1] * qd[0] * qd[1] + m.m[1][1] * qd[1] * qd[1]);
    CHECK(from_model == doctest::Approx(kinetic_energy_by_differences(p, example.home_q_rad, qd)).epsilon(1e-6));
  }
  PlanarSimulationConfig config;
  config.start_q_rad = Vec2{{0.1, -0.2}};
  PlanarPlant plant(p, config);
  const auto counts = plant.sensor_counts();
  const double step = p.sensor_step_rad[0];
  CHECK(counts[0] == static_cast<int>(std::nearbyint((-13.0 * 0.1 + 2.0 * -0.2) / step)));
  CHECK(counts[1] == static_cast<int>(std::nearbyint((-13.0 * -0.2) / step)));
  plant.hold_motor_torques(Vec2{{0.01, 0.005}});
  CHECK(plant.joint_torque_N_m()[0] == doctest::Approx(-0.13));
  CHECK(plant.joint_torque_N_m()[1] == doctest::Approx(0.02 - 0.065));
  const Vec2 back = motor_torques_for_joint_torques(p, plant.joint_torque_N_m());
  CHECK(back[0] == doctest::Approx(0.01));
  CHECK(back[1] == doctest::Approx(0.005));
}

TEST_CASE("planar plant: driven toward where a five-bar cannot close, it stays finite and closed") {
  // Short distal links (the elbows can pull apart further than they reach) and no stops:
  // the plant either slows to the edge (its inertia grows without bound there) or, when a
  // step would leave the closable range, stops the joints and counts a fault.
  PlanarPlantExample example = example_haply2diy_v3_plant();
  PlanarPlantParameters& p = example.parameters;
  p.linkage.five_bar.distal_1_m = p.linkage.five_bar.distal_2_m = 0.06;
  p.stop_min_rad = Vec2{{-kNoLimit, -kNoLimit}};
  p.stop_max_rad = Vec2{{kNoLimit, kNoLimit}};
  PlanarSimulationConfig config;
  config.start_q_rad = example.home_q_rad;
  PlanarPlant plant(p, config);
  plant.hold_motor_torques(Vec2{{0.1, -0.1}});  // spread the elbows apart
  for (int k = 0; k < 2000; ++k) {
    plant.advance(1e-3);
    REQUIRE(all_finite(plant.q_rad()));
    REQUIRE(all_finite(plant.q_dot_rad_per_s()));
    REQUIRE(plant.pose().valid);
  }
  MESSAGE("five-bar pushed to its edge: ", plant.linkage_faults(), " substeps refused");
  const Vec2 gap = plant.pose().elbow_2_m - plant.pose().elbow_1_m;
  CHECK(norm(gap) > 0.115);  // it did get to the edge (0.12 m)
}
