// The device model: the profile chooses the sensor (an MR sensor that wraps, or an
// encoder that does not) and the duty law (the Hapkit's sqrt law, or linear), and the
// tick's sensing and command go through the compiled model.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/devices/device_model.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/devices/profile.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/runner.hpp"
#include "engine/scene/step.hpp"
#include "engine/scene/tick_state.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// The shipped Hapkit 3.0 profile as JSON, to vary one part of.
nlohmann::json hapkit3_json() {
  std::ifstream in(test::source_path("environments/devices/hapkit3.json"));
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

// The Hapkit with an encoder in place of its MR sensor: same counts-to-angle map.
nlohmann::json encoder_hapkit_json() {
  nlohmann::json j = hapkit3_json();
  j["name"] = "hapkit-encoder";
  j["sensor"].erase("min_counts");
  j["sensor"].erase("span_counts");
  j["sensor"].erase("flip_threshold_counts");
  j["sensor"]["type"] = "encoder";
  return j;
}

DeviceProfile profile_of(const nlohmann::json& j) { return parse_device_profile(j.dump(), "kit.json"); }

std::string profile_error(const nlohmann::json& j) {
  return test::input_error_of([&] { profile_of(j); });
}

}  // namespace

TEST_CASE("device model: the shipped profile is an MR sensor with the sqrt law, as before") {
  const DeviceProfile hapkit = profile_of(hapkit3_json());
  CHECK(hapkit.sensor.kind == SensorKind::mr);
  CHECK(hapkit.drive.duty_law == DutyLaw::sqrt);
  CHECK(compile_device_model(hapkit).unwraps);
}

TEST_CASE("device model: an MR sensor unwraps a jump across its period, an encoder's counter passes through") {
  const DeviceModel mr = compile_device_model(profile_of(hapkit3_json()));
  const DeviceModel encoder = compile_device_model(profile_of(encoder_hapkit_json()));
  CHECK_FALSE(encoder.unwraps);
  SensorState mr_state = make_sensor_state(mr);
  SensorState encoder_state = make_sensor_state(encoder);
  // 100 -> 900 counts: for the MR sensor a wrap (a jump above its 700-count threshold),
  // for the encoder 800 counts of real motion.
  sense_position_m(mr, 100, &mr_state);
  sense_position_m(encoder, 100, &encoder_state);
  const double mr_x_m = sense_position_m(mr, 900, &mr_state);
  const double encoder_x_m = sense_position_m(encoder, 900, &encoder_state);
  CHECK(mr_state.unwrapped_counts == 900 - 922);
  CHECK(encoder_state.unwrapped_counts == 900);
  CHECK(encoder_x_m == counts_to_position_m(encoder.kinematics, 900));
  CHECK(mr_x_m == counts_to_position_m(mr.kinematics, 900 - 922));
  // Counts far beyond one MR period (and negative) stay as they are.
  CHECK(sense_position_m(encoder, -250000, &encoder_state) == counts_to_position_m(encoder.kinematics, -250000));
}

TEST_CASE("device model: the linear duty law gives duty = torque / Km, the simulator inverts either law") {
  nlohmann::json j = hapkit3_json();
  j["drive"]["duty_law"] = "linear";
  const DeviceProfile linear = profile_of(j);
  const DeviceProfile hapkit = profile_of(hapkit3_json());
  const double force_N = 1.5;
  const Kinematics k = compile_kinematics(linear);
  const double torque_N_m = k.torque_N_m_per_N * force_N;
  CHECK(force_to_motor(linear, force_N).duty == doctest::Approx(torque_N_m / 0.03).epsilon(1e-12));
  CHECK(force_to_motor(hapkit, force_N).duty == doctest::Approx(std::sqrt(torque_N_m / 0.03)).epsilon(1e-12));
  CHECK(motor_to_force_N(linear, force_to_motor(linear, force_N)) == doctest::Approx(force_N).epsilon(1e-12));
  CHECK(motor_to_force_N(linear, force_to_motor(linear, -force_N)) == doctest::Approx(-force_N).epsilon(1e-12));
  // Both laws reach the same torque at full duty.
  CHECK(max_motor_force_N(linear) == doctest::Approx(max_motor_force_N(hapkit)).epsilon(1e-12));
}

TEST_CASE("device model: a simulated encoder Hapkit is tracked across what would be many MR periods") {
  const Scene scene = test::scene_from(R"({"device": "hapkit3", "effects": [{"type": "damper", "damping": 0.5}]})");
  Scene encoder_scene = scene;
  encoder_scene.device = profile_of(encoder_hapkit_json());
  encoder_scene.device_model = compile_device_model(encoder_scene.device);
  SimulationConfig config;
  config.hand.motion = HandMotion::sweep;  // across the workspace: about 8 MR periods
  SimulatedHapkit device(encoder_scene.device, config);
  TickState state = make_tick_state(encoder_scene);
  const double count_m = std::abs(counts_to_position_m(encoder_scene.device, 1.0) -
                                  counts_to_position_m(encoder_scene.device, 0.0));
  double farthest_m = 0.0;
  double worst_error_m = 0.0;
  for (int tick = 0; tick < 3000; ++tick) {
    step(encoder_scene, device.read(), &state);
    worst_error_m = std::max(worst_error_m, std::abs(state.x_m - device.x_m()));
    farthest_m = std::max(farthest_m, std::abs(device.x_m()));
    device.write(state.command);
    device.advance(encoder_scene.period_s);
  }
  CHECK(farthest_m > 0.03);                  // the hand went far beyond one 11 mm MR period
  CHECK(worst_error_m <= count_m);           // and the host never lost it by more than a count
}

TEST_CASE("device model: profile errors for the sensor type and duty law name the key") {
  nlohmann::json j = hapkit3_json();
  j["sensor"]["type"] = "hall";
  CHECK(profile_error(j).find("kit.json: /sensor/type") != std::string::npos);
  j = encoder_hapkit_json();
  j["sensor"]["span_counts"] = 922;
  CHECK(profile_error(j) == "kit.json: /sensor/span_counts: not used by an encoder (its counts never wrap): remove it");
  j = hapkit3_json();
  j["drive"]["duty_law"] = "cubic";
  CHECK(profile_error(j).find("kit.json: /drive/duty_law") != std::string::npos);
}

TEST_CASE("device model: the firmware's devices refuse an encoder profile, naming it") {
  const DeviceProfile encoder = profile_of(encoder_hapkit_json());
  const std::string serial = test::input_error_of([&] { open_device("serial:/dev/null", encoder, {}, {}); });
  CHECK(serial == "--device serial: profile \"hapkit-encoder\" has an encoder, but the hapscene firmware reads the "
                  "Hapkit's MR sensor (in kit.json: /sensor/type)");
  const std::string hil = test::input_error_of([&] { open_device("hil", encoder, {}, {}); });
  CHECK(hil.find("--device hil: profile \"hapkit-encoder\" has an encoder") == 0);
}
