// The simulated 2-DOF device: what the host commands through a profile's drives is the
// force the plant feels at the handle, and its readings are what the profile's sensors
// would give, for every shipped planar profile.
#include <doctest/doctest.h>

#include <string>

#include "engine/devices/planar/planar_tick.hpp"
#include "engine/devices/planar/simulated_planar.hpp"

using namespace hapscene;

TEST_CASE("simulated planar device: the commanded handle force is the force the plant feels") {
  for (const std::string name : {"haplink", "hapkit_pantograph", "haply2diy_v1", "haply2diy_v2", "haply2diy_v3"}) {
    CAPTURE(name);
    const PlanarProfile profile = load_planar_profile(name, ".");
    PlanarSimulationConfig config;
    config.start_q_rad = planar_joint_angles_at(profile, profile.home_m);
    SimulatedPlanar device(profile, config);
    const PlanarTickModel model = compile_planar_tick_model(profile);
    PlanarTickSensor sensor = make_sensor_state(model);
    const Vec2 x_m = sense_position_m(model, device.read(), &sensor);
    CHECK(norm(x_m - profile.home_m) < 1e-3);  // within the sensors' quantization
    for (const Vec2 force_N : {Vec2{{0.3, -0.2}}, Vec2{{-0.5, 0.0}}, Vec2{{0.0, 0.4}}}) {
      CAPTURE(force_N[0]);
      CAPTURE(force_N[1]);
      device.write(motor_command(model, sensor, force_N));
      const Vec2 felt_N = device.motor_force_N();
      // The sensed pose's Jacobian against the true pose's: equal within quantization.
      CHECK(felt_N[0] == doctest::Approx(force_N[0]).epsilon(0.05).scale(0.1));
      CHECK(felt_N[1] == doctest::Approx(force_N[1]).epsilon(0.05).scale(0.1));
    }
  }
}
