#include "engine/devices/planar/simulated_planar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/object_reader.hpp"

namespace hapscene {

PlanarPlantParameters planar_plant_parameters(const PlanarProfile& profile) {
  PlanarPlantParameters p;
  p.linkage = profile.linkage;
  // The links' lengths, in the order the profile lists their masses.
  double lengths_m[4]{};
  if (profile.linkage.family == LinkageFamily::serial_2r) {
    lengths_m[0] = profile.linkage.serial.link_a_m;
    lengths_m[1] = profile.linkage.serial.link_b_m;
  } else {
    const FiveBarGeometry& g = profile.linkage.five_bar;
    lengths_m[0] = g.proximal_1_m;
    lengths_m[1] = g.proximal_2_m;
    lengths_m[2] = g.distal_1_m;
    lengths_m[3] = g.distal_2_m;
  }
  const PlanarPlantEstimates& plant = profile.plant;
  for (int i = 0; i < plant.link_count && i < 4; ++i) {
    const PlanarLinkMass& link = plant.links[static_cast<std::size_t>(i)];
    p.links[i] = LinkBody{link.mass_kg, lengths_m[i] > 0.0 ? link.center_of_mass_m / lengths_m[i] : 0.5,
                          link.inertia_kg_m2};
  }
  p.handle_mass_kg = plant.handle_mass_kg;
  p.motor_to_joint = Matrix2{};  // identity: the device hands the plant joint torques
  p.rotor_inertia_kg_m2 = plant.rotor_inertia_kg_m2;
  p.viscous_N_m_s_per_rad = plant.viscous_N_m_s_per_rad;
  p.coulomb_N_m = plant.coulomb_N_m;
  // The profile's stops are of the sensed angles; the plant's of the linkage's joints.
  // With a coupling (q2 = sensed 2 + c q1) joint 2's stops widen by the most c q1 adds,
  // so a pose within the sensed stops never starts in contact.
  const double coupling_margin_rad =
      std::fabs(profile.coupling) *
      std::max(std::fabs(plant.end_stops_rad[0][0]), std::fabs(plant.end_stops_rad[0][1]));
  for (int i = 0; i < 2; ++i) {
    const double margin_rad = i == 1 ? coupling_margin_rad : 0.0;
    p.stop_min_rad[i] = plant.end_stops_rad[static_cast<std::size_t>(i)][0] - margin_rad;
    p.stop_max_rad[i] = plant.end_stops_rad[static_cast<std::size_t>(i)][1] + margin_rad;
    p.stop_stiffness_N_m_per_rad[i] = plant.end_stop_stiffness_N_m_per_rad;
    // Critically damped against the joint's own inertia would need the pose; a small
    // fixed fraction keeps contacts from ringing.
    p.stop_damping_N_m_s_per_rad[i] = 0.002 * plant.end_stop_stiffness_N_m_per_rad;
  }
  // The plant's own sensor model is not read (the device reads through the profile's
  // sensors); any positive step will do.
  p.sensor_step_rad = Vec2{{1e-3, 1e-3}};
  return p;
}

Vec2 planar_joint_angles_at(const PlanarProfile& profile, const Vec2& handle_m) {
  // Coarse search: the pose nearest the target on a grid of joint angles within the
  // joints' end stops (of the sensed angles, before the coupling), so that of the
  // linkage's assembly branches the one the device is built in is found.
  constexpr int kSteps = 48;
  const auto& stops = profile.plant.end_stops_rad;
  Vec2 best_q{};
  double best_m = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= kSteps; ++j) {
      const double q1 = stops[0][0] + (stops[0][1] - stops[0][0]) * i / kSteps;
      const double sensed_2 = stops[1][0] + (stops[1][1] - stops[1][0]) * j / kSteps;
      const Vec2 q{{q1, sensed_2 + profile.coupling * q1}};
      const LinkagePose pose = solve_linkage(profile.linkage, q);
      if (!pose.valid) continue;
      const double distance_m = norm(pose.handle_m - handle_m);
      if (distance_m < best_m) {
        best_m = distance_m;
        best_q = q;
      }
    }
  }
  Vec2 q{};
  if (!std::isfinite(best_m) || !joint_angles_for_handle(profile.linkage, handle_m, best_q, &q)) {
    throw InputError(printf_string("the %s cannot put its handle at (%s, %s) m (in %s and /plant/end_stops: the "
                                   "linkage and the joints' travel)",
                                   profile.name.c_str(), format_number(handle_m[0]).c_str(),
                                   format_number(handle_m[1]).c_str(),
                                   profile_place(profile.source, "/kinematics").c_str()));
  }
  return q;
}

SimulatedPlanar::SimulatedPlanar(const PlanarProfile& profile, const PlanarSimulationConfig& config)
    : model_(compile_planar_model(profile)), plant_(planar_plant_parameters(profile), config) {
  plant_.follow(&pointer_);
}

PlanarReading SimulatedPlanar::read() noexcept { return planar_reading_for(model_, plant_.q_rad()); }

void SimulatedPlanar::write(const PlanarMotorCommand& command) noexcept {
  joint_torque_N_m_ = joint_torques_from_motor_N_m(model_, planar_command_torques_N_m(model_, command));
  plant_.hold_motor_torques(joint_torque_N_m_);
}

Vec2 SimulatedPlanar::motor_force_N() const noexcept {
  return handle_force_from_joint_torques_N(plant_.pose().jacobian, joint_torque_N_m_);
}

}  // namespace hapscene
