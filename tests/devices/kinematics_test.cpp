// Hapkit kinematics against the reference formulas, round trips, and the MR sensor's
// flip counting.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "engine/devices/kinematics.hpp"
#include "engine/devices/profile.hpp"
#include "protocol/flip_counter.hpp"

using namespace hapscene;

namespace {
const DeviceProfile& hapkit3() {
  static const DeviceProfile profile = load_device_profile("hapkit3", ".");
  return profile;
}
}  // namespace

TEST_CASE("kinematics: counts -> sector angle -> handle position (reference fit)") {
  const DeviceProfile& p = hapkit3();
  // theta_deg = -0.0107 * counts + 4.9513; xh = rh * theta_rad.
  const double counts = 300.0;
  const double theta_rad = (-0.0107 * counts + 4.9513) * std::numbers::pi / 180.0;
  CHECK(counts_to_position_m(p, counts) == doctest::Approx(0.065659 * theta_rad).epsilon(1e-12));
  // About 12-13 um of handle travel per count.
  const double per_count_m = counts_to_position_m(p, 0.0) - counts_to_position_m(p, 1.0);
  CHECK(per_count_m == doctest::Approx(12.26e-6).epsilon(0.01));
}

TEST_CASE("kinematics: position and counts round trip") {
  const DeviceProfile& p = hapkit3();
  for (double x_m : {-0.05, -0.012, 0.0, 0.003, 0.045}) {
    CAPTURE(x_m);
    CHECK(counts_to_position_m(p, position_to_counts(p, x_m)) == doctest::Approx(x_m).epsilon(1e-12));
  }
}

TEST_CASE("kinematics: force -> motor torque -> duty, as the board needs it") {
  const DeviceProfile& p = hapkit3();
  // Tp = rp / rs * rh * F; duty = sqrt(|Tp| / Km).
  const double force_N = 2.0;
  const double torque = 0.004191 / 0.073152 * 0.065659 * force_N;
  const MotorCommand command = force_to_motor(p, force_N);
  CHECK(command.duty == doctest::Approx(std::sqrt(torque / 0.03)).epsilon(1e-12));
  CHECK(command.direction_high);
  CHECK_FALSE(force_to_motor(p, -force_N).direction_high);
  CHECK(force_to_motor(p, -force_N).duty == command.duty);
  // And back: the force a duty produces.
  CHECK(motor_to_force_N(p, command) == doctest::Approx(force_N).epsilon(1e-12));
  CHECK(motor_to_force_N(p, force_to_motor(p, -1.5)) == doctest::Approx(-1.5).epsilon(1e-12));
  CHECK(force_to_motor(p, 0.0).duty == 0.0);
}

TEST_CASE("kinematics: duty saturates at duty_max (about 8 N for Km = 0.03)") {
  const DeviceProfile& p = hapkit3();
  CHECK(max_motor_force_N(p) == doctest::Approx(7.97).epsilon(0.005));
  CHECK(force_to_motor(p, 50.0).duty == 1.0);
  DeviceProfile capped = p;
  capped.drive.duty_max = 0.95;
  CHECK(force_to_motor(capped, 50.0).duty == 0.95);
}

TEST_CASE("kinematics: the direction sign of the profile flips the pin") {
  DeviceProfile p = hapkit3();
  p.drive.direction_sign = -1;
  CHECK_FALSE(force_to_motor(p, 1.0).direction_high);
  CHECK(motor_to_force_N(p, force_to_motor(p, 1.0)) == doctest::Approx(1.0));
}

TEST_CASE("flip counter: unwraps the MR sensor across periods in both directions") {
  FlipCounter counter{.threshold_counts = 700, .span_counts = 922};
  CHECK(counter.update(500) == 500);
  CHECK(counter.update(960) == 960);
  CHECK(counter.update(60) == 60 + 922);   // wrapped past the top
  CHECK(counter.update(100) == 100 + 922);
  CHECK(counter.update(965) == 965);       // and back down
  CHECK(counter.update(55) == 55 + 922);
  CHECK(counter.update(960) == 960);
  CHECK(counter.update(900) == 900);
  CHECK(counter.update(60) == 60 + 922);
  CHECK(counter.update(970) == 970);
  CHECK(counter.update(60) == 60 + 922);
  CHECK(counter.update(80) == 80 + 922);
  CHECK(counter.update(900) == 900);       // jump of 820 < -700: down a period
  CHECK(counter.update(55) == 55 + 922);
}

TEST_CASE("profile: bad profiles fail with the file and the place") {
  const std::string good = R"({"name": "x",
    "sensor": {"counts_to_deg_slope": -0.0107, "counts_to_deg_offset": 4.95, "min_counts": 50,
               "span_counts": 922, "flip_threshold_counts": 700},
    "drive": {"handle_radius": 0.065, "pulley_radius": 0.004, "sector_radius": 0.073,
              "motor_constant": 0.03, "duty_max": 1, "direction_sign": 1, "pwm_levels": 255},
    "limits": {"max_force": 5, "slew_limit": 4000, "workspace": [-0.05, 0.05], "soft_start": 0.5,
               "soft_start_threshold": 0.5},
    "plant": {"mass": 0.04, "viscous": 0.4, "coulomb": 0.1, "end_stops": [-0.06, 0.06],
              "end_stop_stiffness": 20000, "sensor_noise_counts": 0}})";
  CHECK(parse_device_profile(good, "x.json").drive.pwm_levels == 255);

  const auto error_with = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    try {
      parse_device_profile(text, "x.json");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("(no error)");
  };
  CHECK(error_with("\"duty_max\": 1", "\"duty_max\": 1.5") == "x.json: /drive/duty_max: must be <= 1");
  CHECK(error_with("\"direction_sign\": 1", "\"direction_sign\": 0") ==
        "x.json: /drive/direction_sign: must be 1 or -1");
  CHECK(error_with("\"pwm_levels\": 255", "\"pwm_levels\": 2.5") ==
        "x.json: /drive/pwm_levels: expected a whole number, got 2.5");
  CHECK(error_with("[-0.05, 0.05]", "[0.05, -0.05]") ==
        "x.json: /limits/workspace: low must be below high");
  CHECK(error_with("[-0.06, 0.06]", "[-0.06]") ==
        "x.json: /plant/end_stops: expected [low, high] as an array of two length values, got array");
  CHECK(error_with("[-0.06, 0.06]", "[\"-6 cm\", \"6 N\"]") ==
        "x.json: /plant/end_stops/1: expected a length (m), got a force (\"6 N\")");
  CHECK(error_with("\"flip_threshold_counts\": 700", "\"flip_threshold_counts\": 922") ==
        "x.json: /sensor/flip_threshold_counts: must be in [1, 921], got 922");
  CHECK(error_with("\"mass\": 0.04", "\"mas\": 0.04") == "x.json: /plant/mas: unknown key \"mas\" (did you mean \"mass\"?)");
}
