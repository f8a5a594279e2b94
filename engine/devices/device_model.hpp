#pragma once
// The device-specific half of every tick, compiled from a device profile: what the device
// reads becomes the handle position, and the force on the handle becomes what the
// device's motor driver takes. step() calls sense_position_m() and motor_command() and
// knows nothing of sensors, drives or duty laws.
//
// The profile chooses the parts: the sensor (an MR sensor whose raw counts wrap every
// half turn of the motor shaft, unwrapped by the FlipCounter the firmware shares; or an
// encoder's continuous counter), a linear map from counts to sector angle and the capstan
// to the handle; force to motor torque through the same ratios, then the duty law (the
// Hapkit's sqrt law, or linear) and a direction pin (engine/devices/kinematics.hpp).
// docs/explanation/n-axis.md says how models for other devices and more axes plug in here.
#include <cstdint>

#include "engine/devices/device.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/devices/profile.hpp"
#include "protocol/flip_counter.hpp"

namespace hapscene {

// What the sensor stage of one run keeps (TickState::sensor).
struct SensorState {
  FlipCounter flip_counter;
  std::int32_t raw_counts{};        // the latest reading as the device gave it
  std::int32_t unwrapped_counts{};  // after unwrapping
};

// A profile compiled for the tick: immutable, read through a const reference.
struct DeviceModel {
  Kinematics kinematics;
  bool unwraps{true};  // an MR sensor's wrapping counts; false: an encoder's continuous ones
  std::int32_t flip_threshold_counts{};
  std::int32_t span_counts{};
};

DeviceModel compile_device_model(const DeviceProfile& profile) noexcept;

// A fresh sensor stage for a run (nothing unwrapped yet).
SensorState make_sensor_state(const DeviceModel& model) noexcept;

// Sensor stage: one raw reading to the handle position. An encoder's counter goes through
// the same flip counter, set up never to flip (make_sensor_state), so the tick has no
// branch on the sensor kind.
inline double sense_position_m(const DeviceModel& model, std::int32_t raw_counts, SensorState* sensor) noexcept {
  sensor->raw_counts = raw_counts;
  sensor->unwrapped_counts = sensor->flip_counter.update(raw_counts);
  return counts_to_position_m(model.kinematics, sensor->unwrapped_counts);
}

// Command stage: the force on the handle to the motor driver's command.
// (The sensor state is where a multi-axis model keeps the pose its command needs: the
// Jacobian; a 1-DOF model does not read it.)
inline MotorCommand motor_command(const DeviceModel& model, const SensorState& sensor,
                                  double force_N) noexcept {
  (void)sensor;
  return force_to_motor(model.kinematics, force_N);
}

// A 1-DOF capstan has no singular pose, and its one motor clamps its duty (what the
// safety stage's force limit already bounds): the tick's checks compile to nothing.
constexpr PoseTrust pose_trust(const DeviceModel&, const SensorState&) noexcept { return PoseTrust::trusted; }
constexpr bool command_saturated(const MotorCommand&) noexcept { return false; }

// The capstan model's tick stages (device.hpp): one family, nothing compiled ahead; a
// reading within the flip counter's window is steady (it cannot be a flip of the sensor).
template <>
struct TickStages<DeviceModel> {
  enum class Variant { general };
  static constexpr Variant kGeneral = Variant::general;
  static constexpr bool kVariantsAhead = false;
  template <typename F>
  static constexpr bool dispatch(const DeviceModel& /*model*/, F&& /*f*/) noexcept { return false; }
  template <Variant>
  [[gnu::always_inline]] static double sense(const DeviceModel& model, std::int32_t raw_counts,
                                             SensorState* sensor) noexcept {
    return sense_position_m(model, raw_counts, sensor);
  }
  template <Variant>
  [[gnu::always_inline]] static void command(const DeviceModel& model, const SensorState& sensor, double force_N,
                                             MotorCommand* command) noexcept {
    *command = motor_command(model, sensor, force_N);
  }
  static constexpr bool kSteadyTick = true;
  [[gnu::always_inline]] static bool steady_reading(const SensorState& sensor, std::int32_t raw_counts) noexcept {
    return sensor.flip_counter.within_window(raw_counts);
  }
};

}  // namespace hapscene
