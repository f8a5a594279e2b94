#include "engine/devices/planar/planar_plant_examples.hpp"

#include <numbers>

namespace hapscene {
namespace {

constexpr double kPi = std::numbers::pi;

double degrees(double d) { return d * kPi / 180.0; }

// A slender link's inertia about its centre.
double rod_inertia(double mass_kg, double length_m) { return mass_kg * length_m * length_m / 12.0; }

}  // namespace

PlanarPlantExample example_haplink_plant() {
  PlanarPlantExample e;
  PlanarPlantParameters& p = e.parameters;
  p.linkage.family = LinkageFamily::serial_2r;
  p.linkage.serial = SerialArmGeometry{Vec2{}, 0.087, 0.100, 0.8727, -1.4};
  // Link a carries its Hapkit sector near the pivot: centre of mass at a fifth of the link,
  // most of the inertia in the sector (about 1.2e-4 kg m^2, close to the Hapkit's
  // 0.04 kg effective mass at its 66 mm handle). Link b: a 30 g rod.
  p.links[0] = LinkBody{0.05, 0.2, 1.2e-4};
  p.links[1] = LinkBody{0.03, 0.5, rod_inertia(0.03, 0.100)};
  p.handle_mass_kg = 0.01;
  // Capstan 72 / 5.5: joint = -(5.5 / 72) motor, so joint torque = -(72 / 5.5) motor torque.
  const double ratio = -72.0 / 5.5;
  p.motor_to_joint = Matrix2{{{ratio, 0.0}, {0.0, ratio}}};
  p.rotor_inertia_kg_m2 = Vec2{{1e-7, 1e-7}};
  p.motor_torque_limit_N_m = Vec2{{1.0 / 65.13, 1.0 / 65.13}};  // full duty in the linear law
  p.viscous_N_m_s_per_rad = Vec2{{1e-3, 1e-3}};
  p.coulomb_N_m = Vec2{{5e-3, 5e-3}};
  p.stop_min_rad = Vec2{{-1.0, -1.2}};
  p.stop_max_rad = Vec2{{1.0, 1.0}};
  p.stop_stiffness_N_m_per_rad = Vec2{{50.0, 50.0}};
  p.stop_damping_N_m_s_per_rad = Vec2{{0.1, 0.1}};
  p.sensor_step_rad = Vec2{{2.0 * kPi / 48.0, 2.0 * kPi / 48.0}};
  e.home_q_rad = Vec2{};
  return e;
}

PlanarPlantExample example_haply2diy_v3_plant() {
  PlanarPlantExample e;
  PlanarPlantParameters& p = e.parameters;
  p.linkage.family = LinkageFamily::five_bar;
  p.linkage.five_bar = FiveBarGeometry{Vec2{}, Vec2{{0.038, 0.0}}, 0.07, 0.07, 0.09, 0.09, 1};
  p.links[0] = LinkBody{0.02, 0.5, rod_inertia(0.02, 0.07)};
  p.links[1] = LinkBody{0.02, 0.5, rod_inertia(0.02, 0.07)};
  p.links[2] = LinkBody{0.02, 0.5, rod_inertia(0.02, 0.09)};
  p.links[3] = LinkBody{0.02, 0.5, rod_inertia(0.02, 0.09)};
  p.handle_mass_kg = 0.01;
  p.motor_to_joint = Matrix2{};
  p.rotor_inertia_kg_m2 = Vec2{{3e-6, 3e-6}};
  p.motor_torque_limit_N_m = Vec2{{0.123, 0.123}};
  p.viscous_N_m_s_per_rad = Vec2{{2e-4, 2e-4}};
  p.coulomb_N_m = Vec2{{1e-3, 1e-3}};
  // Stops that keep the linkage closable and away from its singular poses.
  p.stop_min_rad = Vec2{{degrees(95.0), degrees(10.0)}};
  p.stop_max_rad = Vec2{{degrees(170.0), degrees(85.0)}};
  p.stop_stiffness_N_m_per_rad = Vec2{{20.0, 20.0}};
  p.stop_damping_N_m_s_per_rad = Vec2{{0.05, 0.05}};
  p.sensor_step_rad = Vec2{{2.0 * kPi / 4880.0, 2.0 * kPi / 4880.0}};
  e.home_q_rad = Vec2{{degrees(120.0), degrees(60.0)}};
  return e;
}

}  // namespace hapscene
