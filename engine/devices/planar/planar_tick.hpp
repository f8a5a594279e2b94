#pragma once
// A planar (2-DOF) device as the scene's tick sees it: the device model functions that
// step() calls for every device family (sense_position_m, motor_command, pose_hold) and
// what a 2-joint device reads and takes (DeviceIo<2>). docs/explanation/n-axis.md draws the seam.
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
  // condition_limit + 1 / condition_limit: the test of the limit without a square root
  // (see pose_trust).
  double condition_bound{};
};

PlanarTickModel compile_planar_tick_model(const PlanarProfile& profile) noexcept;

// The sensor stage's per-run state: the joints' unwrapping and the pose of this tick (its
// Jacobian is what the command stage needs; its condition number, when wanted, is
// condition_number(pose.jacobian)).
struct PlanarTickSensor {
  PlanarSensorState joints;
  LinkagePose pose;
};

PlanarTickSensor make_sensor_state(const PlanarTickModel& model) noexcept;

// Sensor stage: the joints' readings to the handle position (task frame, m). kFamily: the
// model's family, or general (PlanarFamily).
template <PlanarFamily kFamily = PlanarFamily::general>
[[gnu::always_inline]] inline Vec2 sense_position_m(const PlanarTickModel& model, const PlanarReading& reading,
                             PlanarTickSensor* sensor) noexcept {
  sense_planar<kFamily>(model.model, reading, &sensor->joints, &sensor->pose);
  return sensor->pose.handle_m;
}

// Whether the pose lets force be rendered: a linkage that cannot close at the sensed
// angles (or a non-finite reading) renders nothing; a pose whose Jacobian is worse
// conditioned than the profile's limit L (near a singularity, where a small force needs a
// huge torque and the position is ill-sensed) ramps force out.
// The test needs no square root: with s1 >= s2 the singular values of J, its condition
// number k = s1 / s2 has k + 1 / k = (s1^2 + s2^2) / (s1 s2) = |J|_F^2 / |det J|, which
// grows with k for k >= 1, so k <= L (L >= 1) exactly when |J|_F^2 <= (L + 1/L) |det J|.
// A singular J (det 0) or a non-finite one fails it, as an infinite condition number does.
[[gnu::always_inline]] inline PoseTrust pose_trust(const PlanarTickModel& model,
                                                   const PlanarTickSensor& sensor) noexcept {
  if (!sensor.pose.valid) return PoseTrust::invalid;
  const Jacobian2& j = sensor.pose.jacobian;
  const double a = j.m[0][0], b = j.m[0][1], c = j.m[1][0], d = j.m[1][1];
  const double frobenius_sq = a * a + b * b + c * c + d * d;
  const double det = std::fabs(a * d - b * c);
  const bool within = frobenius_sq <= model.condition_bound * det && det > 0.0 &&
                      frobenius_sq < std::numeric_limits<double>::infinity();
  return within ? PoseTrust::trusted : PoseTrust::near_singular;
}

// Command stage: J^T F at this tick's pose, to each motor's command (both scaled alike
// when one saturates), written to `command`.
template <PlanarFamily kFamily = PlanarFamily::general>
[[gnu::always_inline]] inline void motor_command(const PlanarTickModel& model, const PlanarTickSensor& sensor,
                                                 const Vec2& force_N, PlanarMotorCommand* command) noexcept {
  planar_motor_command<kFamily>(model.model, sensor.pose.jacobian, force_N, command);
}
inline PlanarMotorCommand motor_command(const PlanarTickModel& model, const PlanarTickSensor& sensor,
                                        const Vec2& force_N) noexcept {
  return planar_motor_command(model.model, sensor.pose.jacobian, force_N);
}

// Whether the command had to scale both motors down (one saturated), for the counters.
inline bool command_saturated(const PlanarMotorCommand& command) noexcept { return command.saturated; }

// The planar model's tick stages (device.hpp): the serial arm with encoders and a linear
// duty law and the five-bar with angles and torques are compiled ahead, each with its
// branches decided; any other family runs the general tick. No steady-reading tick.
template <>
struct TickStages<PlanarTickModel> {
  using Variant = PlanarFamily;
  static constexpr Variant kGeneral = PlanarFamily::general;
  static constexpr bool kVariantsAhead = true;
  template <typename F>
  [[gnu::always_inline]] static bool dispatch(const PlanarTickModel& model, F&& f) noexcept {
    switch (model.model.family) {
      case PlanarFamily::serial_encoders_linear:
        f.template operator()<PlanarFamily::serial_encoders_linear>();
        return true;
      case PlanarFamily::five_bar_angles_torque:
        f.template operator()<PlanarFamily::five_bar_angles_torque>();
        return true;
      case PlanarFamily::general:
        break;
    }
    return false;
  }
  template <Variant kFamily>
  [[gnu::always_inline]] static Vec2 sense(const PlanarTickModel& model, const PlanarReading& reading,
                                           PlanarTickSensor* sensor) noexcept {
    return sense_position_m<kFamily>(model, reading, sensor);
  }
  template <Variant kFamily>
  [[gnu::always_inline]] static void command(const PlanarTickModel& model, const PlanarTickSensor& sensor,
                                             const Vec2& force_N, PlanarMotorCommand* command) noexcept {
    motor_command<kFamily>(model, sensor, force_N, command);
  }
  static constexpr bool kSteadyTick = false;
  static constexpr bool steady_reading(const PlanarTickSensor& /*sensor*/, const PlanarReading& /*reading*/) noexcept {
    return false;
  }
};

}  // namespace hapscene
