#pragma once
// A simulated 2-DOF device: the planar plant of the profile's kinematics family (its
// links' masses, joint friction and end stops from the profile's "plant" estimates),
// read through the profile's own sensors (quantized, MR counts wrapped) and driven
// through its own drives, so the host code sees what it would see on the real device.
// Deterministic.
#include "engine/devices/device.hpp"
#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/planar/planar_plant.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/devices/planar/planar_tick.hpp"

namespace hapscene {

// The plant's parameters from a profile: link bodies, handle mass, rotor inertia (as the
// profile gives it, reflected to the joint), joint friction and end stops (of the joints
// as the linkage takes them; with a coupling, joint 2's widened by what the coupling can
// add, as the plant knows no sensed angles). Motor torques are mapped to
// joint torques by the device (the drive's ratios and coupling), not the plant.
PlanarPlantParameters planar_plant_parameters(const PlanarProfile& profile);

// Joint angles that put the handle at `handle_m` (the profile's home when not given):
// a coarse search of the joint space within the end stops (so the branch the device is
// built in) for a pose near it, refined by Newton's method.
// Throws InputError when the linkage cannot reach it.
Vec2 planar_joint_angles_at(const PlanarProfile& profile, const Vec2& handle_m);

class SimulatedPlanar final : public DeviceOf<2>, public SimulationTruthOf<2> {
 public:
  // `config.start_q_rad` is where the joints start (see planar_joint_angles_at).
  SimulatedPlanar(const PlanarProfile& profile, const PlanarSimulationConfig& config);

  PlanarReading read() noexcept override;
  void write(const PlanarMotorCommand& command) noexcept override;
  void advance(double dt_s) noexcept override { plant_.advance(dt_s); }
  const SimulationTruthOf<2>* truth() const noexcept override { return this; }
  HandPointerOf<2>* hand_pointer() const noexcept override { return &pointer_; }
  bool deadlines_matter() const noexcept override { return false; }

  Vec2 x_m() const noexcept override { return plant_.handle_m(); }
  Vec2 v_m_per_s() const noexcept override { return plant_.handle_velocity_m_per_s(); }
  Vec2 motor_force_N() const noexcept override;
  Vec2 hand_force_N() const noexcept override { return plant_.hand_force_N(); }

  const PlanarPlant& plant() const noexcept { return plant_; }

 private:
  mutable HandPointerOf<2> pointer_;  // a mailbox the live view writes, the plant reads
  PlanarModel model_;
  PlanarPlant plant_;
  Vec2 joint_torque_N_m_{};
};

}  // namespace hapscene
