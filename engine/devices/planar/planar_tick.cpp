#include "engine/devices/planar/planar_tick.hpp"

namespace hapscene {

PlanarTickModel compile_planar_tick_model(const PlanarProfile& profile) noexcept {
  PlanarTickModel model;
  model.model = compile_planar_model(profile);
  model.condition_limit = profile.limits.condition_limit;
  model.condition_bound = model.condition_limit + 1.0 / model.condition_limit;
  return model;
}

PlanarTickSensor make_sensor_state(const PlanarTickModel& model) noexcept {
  PlanarTickSensor sensor;
  sensor.joints = make_planar_sensor_state(model.model);
  return sensor;
}

}  // namespace hapscene
