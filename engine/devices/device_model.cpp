#include "engine/devices/device_model.hpp"

namespace hapscene {

DeviceModel compile_device_model(const DeviceProfile& profile) noexcept {
  DeviceModel model;
  model.kinematics = compile_kinematics(profile);
  model.unwraps = profile.sensor.kind == SensorKind::mr;
  model.flip_threshold_counts = profile.sensor.flip_threshold_counts;
  model.span_counts = profile.sensor.span_counts;
  return model;
}

SensorState make_sensor_state(const DeviceModel& model) noexcept {
  SensorState sensor;
  sensor.flip_counter.threshold_counts = model.flip_threshold_counts;
  sensor.flip_counter.span_counts = model.span_counts;
  return sensor;
}

}  // namespace hapscene
