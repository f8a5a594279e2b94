// Fuzz target: a planar (2-DOF) device profile through its loader, then its compiled
// model over readings and forces, which must give finite poses or invalid ones, and finite
// motor commands within each motor's drive.
#include <cmath>
#include <cstdint>

#include "engine/base/errors.hpp"
#include "engine/devices/planar/planar_model.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hapscene;
  const std::string_view text = fuzz::as_text(data, size);
  PlanarProfile profile;
  try {
    profile = parse_planar_profile(text, "fuzz_planar_profile.json");
  } catch (const InputError&) {
    return 0;
  }
  const PlanarModel model = compile_planar_model(profile);
  PlanarSensorState state = make_planar_sensor_state(model);
  const std::int32_t counts[] = {0, 1, -1, 511, 1000000, INT32_MAX, INT32_MIN};
  const double forces[] = {0.0, 1.0, -3.0, 1e3};
  for (const std::int32_t c1 : counts) {
    for (const std::int32_t c2 : counts) {
      PlanarReading reading;
      reading.counts = {c1, c2};
      reading.angle_deg = Vec2{{c1 * 1e-3, c2 * 1e-3}};
      const LinkagePose pose = sense_planar(model, reading, &state);
      fuzz::fuzz_require(all_finite(pose.handle_m), "planar pose not finite");
      if (!pose.valid) continue;
      for (const double fx : forces) {
        const PlanarMotorCommand command = planar_motor_command(model, pose.jacobian, Vec2{{fx, -0.5 * fx}});
        for (std::size_t i = 0; i < 2; ++i) {
          fuzz::fuzz_require(std::isfinite(command.torque_N_m[static_cast<int>(i)]), "motor torque not finite");
          fuzz::fuzz_require(std::fabs(command.torque_N_m[static_cast<int>(i)]) <= model.joints[i].motor_torque_max_N_m,
                             "motor torque beyond its drive");
          fuzz::fuzz_require(command.motor[i].duty >= 0.0 && command.motor[i].duty <= 1.0, "duty outside [0, 1]");
        }
      }
    }
  }
  return 0;
}
