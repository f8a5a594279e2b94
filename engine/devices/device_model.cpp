#include "engine/devices/device_model.hpp"

#include <cstdint>

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
  // An encoder never wraps: no jump exceeds the largest threshold, and a flip (only an
  // overflowing difference of garbage readings can make one) would shift by 0 counts.
  sensor.flip_counter.threshold_counts = model.unwraps ? model.flip_threshold_counts : INT32_MAX;
  sensor.flip_counter.span_counts = model.unwraps ? model.span_counts : 0;
  return sensor;
}

}  // namespace hapscene
