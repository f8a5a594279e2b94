#pragma once
// A planar (2-DOF) device as the scene's tick sees it: the device model functions that
// step() calls for every device family (sense_position_m, motor_command, pose_hold) and
// what a 2-joint device reads and takes (DeviceIo<2>). docs/n-axis.md draws the seam.
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/devices/device.hpp"
#include "engine/devices/planar/linkage.hpp"
#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/planar/planar_profile.hpp"

namespace hapscene {

// Two joints: each joint's sensor reading (counts, or the angle a board reports) in, each
// motor's command (duty and direction, or a torque) out.
template <>
struct DeviceIo<2> {
  using Reading = PlanarReading;
  using Command = PlanarMotorCommand;
};

// A planar profile compiled for the tick: the joints and linkage, and how close to a
// singular pose force may be rendered.
struct PlanarTickModel {
  PlanarModel model;
  double condition_limit{};  // the Jacobian's condition number past which force ramps out
};

PlanarTickModel compile_planar_tick_model(const PlanarProfile& profile) noexcept;

// The sensor stage's per-run state: the joints' unwrapping and the pose of this tick (its
// Jacobian is what the command stage needs).
struct PlanarTickSensor {
  PlanarSensorState joints;
  LinkagePose pose;
  double condition{};  // the pose's Jacobian condition number (infinity when invalid)
};

PlanarTickSensor make_sensor_state(const PlanarTickModel& model) noexcept;

// Sensor stage: the joints' readings to the handle position (task frame, m).
inline Vec2 sense_position_m(const PlanarTickModel& model, const PlanarReading& reading,
                             PlanarTickSensor* sensor) noexcept {
  sensor->pose = sense_planar(model.model, reading, &sensor->joints);
  sensor->condition = sensor->pose.valid ? condition_number(sensor->pose.jacobian)
                                         : std::numeric_limits<double>::infinity();
  return sensor->pose.handle_m;
}

// Whether the pose lets force be rendered: a linkage that cannot close at the sensed
// angles (or a non-finite reading) renders nothing; a pose whose Jacobian is worse
// conditioned than the profile's limit (near a singularity, where a small force needs a
// huge torque and the position is ill-sensed) ramps force out.
inline PoseTrust pose_trust(const PlanarTickModel& model, const PlanarTickSensor& sensor) noexcept {
  if (!sensor.pose.valid) return PoseTrust::invalid;
  if (!(sensor.condition <= model.condition_limit)) return PoseTrust::near_singular;
  return PoseTrust::trusted;
}

// Command stage: J^T F at this tick's pose, to each motor's command (both scaled alike
// when one saturates).
inline PlanarMotorCommand motor_command(const PlanarTickModel& model, const PlanarTickSensor& sensor,
                                        const Vec2& force_N) noexcept {
  return planar_motor_command(model.model, sensor.pose.jacobian, force_N);
}

// Whether the command had to scale both motors down (one saturated), for the counters.
inline bool command_saturated(const PlanarMotorCommand& command) noexcept { return command.saturated; }

}  // namespace hapscene
