// Every number of a device profile has a finite physical range (docs/reference/
// devices.md): an absurd value is refused with the profile's file and JSON pointer,
// after the environment's /device when the profile is referenced from one.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "engine/devices/profile.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

const std::string kGood = R"({"name": "x",
  "sensor": {"counts_to_deg_slope": -0.0107, "counts_to_deg_offset": 4.95, "min_counts": 50,
             "span_counts": 922, "flip_threshold_counts": 700},
  "drive": {"handle_radius": 0.065, "pulley_radius": 0.004, "sector_radius": 0.073,
            "motor_constant": 0.03, "duty_max": 1, "direction_sign": 1, "pwm_levels": 255},
  "limits": {"max_force": 5, "slew_limit": 4000, "workspace": [-0.05, 0.05], "soft_start": 0.5,
             "soft_start_threshold": 0.5, "slip_force": 5, "slip_step": 2},
  "plant": {"mass": 0.04, "viscous": 0.4, "coulomb": 0.1, "end_stops": [-0.06, 0.06],
            "end_stop_stiffness": 20000, "sensor_noise_counts": 0}})";

// The error of kGood with `from` replaced by `to`.
std::string error_with(const std::string& from, const std::string& to) {
  std::string text = kGood;
  REQUIRE(text.find(from) != std::string::npos);
  text.replace(text.find(from), from.size(), to);
  return test::input_error_of([&] { parse_device_profile(text, "x.json"); });
}

}  // namespace

TEST_CASE("profile ranges: every numeric field refuses an absurd value, naming its pointer") {
  struct Case {
    const char* from;
    const char* to;
    const char* message;
  };
  const std::vector<Case> cases{
      {"\"counts_to_deg_slope\": -0.0107", "\"counts_to_deg_slope\": 1e300",
       "/sensor/counts_to_deg_slope: must be in [-10, -1e-06] or [1e-06, 10] (deg/count), got 1e+300"},
      {"\"counts_to_deg_slope\": -0.0107", "\"counts_to_deg_slope\": -1e-300",
       "/sensor/counts_to_deg_slope: must be in [-10, -1e-06] or [1e-06, 10] (deg/count), got -1e-300"},
      {"\"counts_to_deg_offset\": 4.95", "\"counts_to_deg_offset\": 1e300",
       "/sensor/counts_to_deg_offset: must be in [-3600, 3600], got 1e+300"},
      {"\"handle_radius\": 0.065", "\"handle_radius\": 1e-300",
       "/drive/handle_radius: must be in [0.0001, 1] m, got 1e-300 m"},
      {"\"pulley_radius\": 0.004", "\"pulley_radius\": 1e300", "/drive/pulley_radius: must be in [0.0001, 1] m, got 1e+300 m"},
      {"\"sector_radius\": 0.073", "\"sector_radius\": 2", "/drive/sector_radius: must be in [0.0001, 1] m, got 2 m"},
      {"\"motor_constant\": 0.03", "\"motor_constant\": 1e300",
       "/drive/motor_constant: must be in [1e-06, 100], got 1e+300"},
      {"\"max_force\": 5", "\"max_force\": 1e300", "/limits/max_force: must be in (0, 1000] N, got 1e+300 N"},
      {"\"slew_limit\": 4000", "\"slew_limit\": 1e300",
       "/limits/slew_limit: must be in (0, 100000000] N/s, got 1e+300 N/s"},
      {"\"workspace\": [-0.05, 0.05]", "\"workspace\": [-1e300, 0.05]",
       "/limits/workspace/0: must be in [-1000, 1000] m, got -1e+300 m"},
      {"\"soft_start\": 0.5", "\"soft_start\": 1e300", "/limits/soft_start: must be in [0, 60] s, got 1e+300 s"},
      {"\"soft_start_threshold\": 0.5", "\"soft_start_threshold\": 1e300",
       "/limits/soft_start_threshold: must be in [0, 1000] N, got 1e+300 N"},
      {"\"slip_force\": 5", "\"slip_force\": 1e300", "/limits/slip_force: must be in (0, 1000] N, got 1e+300 N"},
      {"\"slip_step\": 2", "\"slip_step\": 1e300", "/limits/slip_step: must be in (0, 1000] N, got 1e+300 N"},
      {"\"mass\": 0.04", "\"mass\": 1e-300", "/plant/mass: must be in [0.0001, 100] kg, got 1e-300 kg"},
      {"\"viscous\": 0.4", "\"viscous\": 1e300", "/plant/viscous: must be in [0, 10000] N*s/m, got 1e+300 N*s/m"},
      {"\"coulomb\": 0.1", "\"coulomb\": 1e300", "/plant/coulomb: must be in [0, 1000] N, got 1e+300 N"},
      {"\"end_stops\": [-0.06, 0.06]", "\"end_stops\": [-0.06, 1e300]",
       "/plant/end_stops/1: must be in [-1000, 1000] m, got 1e+300 m"},
      {"\"end_stop_stiffness\": 20000", "\"end_stop_stiffness\": 1e300",
       "/plant/end_stop_stiffness: must be in (0, 10000000] N/m, got 1e+300 N/m"},
      {"\"sensor_noise_counts\": 0", "\"sensor_noise_counts\": 1e300",
       "/plant/sensor_noise_counts: must be in [0, 1000], got 1e+300"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.to);
    CHECK(error_with(c.from, c.to) == std::string("x.json: ") + c.message);
  }
  // Signs keep their words.
  CHECK(error_with("\"mass\": 0.04", "\"mass\": 0") == "x.json: /plant/mass: must be > 0, got 0 kg");
  CHECK(error_with("\"viscous\": 0.4", "\"viscous\": -1") == "x.json: /plant/viscous: must be >= 0, got -1 N*s/m");
}

TEST_CASE("profile ranges: the shipped profile and the ends of each range load") {
  CHECK(load_device_profile("hapkit3", ".").limits.max_force_N == 6.0);
  std::string text = kGood;
  const auto set = [&](const std::string& from, const std::string& to) {
    REQUIRE(text.find(from) != std::string::npos);
    text.replace(text.find(from), from.size(), to);
  };
  set("\"mass\": 0.04", "\"mass\": 1e-4");
  set("\"max_force\": 5", "\"max_force\": 1000");
  set("\"slew_limit\": 4000", "\"slew_limit\": 1e8");
  set("\"soft_start\": 0.5", "\"soft_start\": 60");
  set("\"end_stop_stiffness\": 20000", "\"end_stop_stiffness\": 1e7");
  set("\"counts_to_deg_slope\": -0.0107", "\"counts_to_deg_slope\": 10");
  const DeviceProfile profile = parse_device_profile(text, "x.json");
  CHECK(profile.plant.mass_kg == 1e-4);
  CHECK(profile.limits.slew_limit_N_per_s == 1e8);
}

TEST_CASE("profile ranges: a referenced profile's absurd value names the environment, /device and the profile") {
  const test::ScratchFolder folder("profile_ranges");
  std::string text = kGood;
  text.replace(text.find("\"mass\": 0.04"), 12, "\"mass\": 1e-300");
  const std::string profile = folder.write("kit.json", text).string();
  const std::string env =
      folder.write("env.json", R"({"device": "kit.json", "effects": [{"type": "spring", "stiffness": 100}]})").string();
  const std::string message = env + ": /device: " + profile + ": /plant/mass: must be in [0.0001, 100] kg, got 1e-300 kg";
  CHECK(test::input_error_of([&] { load_environment_file(env); }) == message);
  const auto probe = test::run_cli("probe " + env + " --x 0:0.01:0.01");
  CHECK(probe.exit_code == 2);
  CHECK(probe.out.empty());
  CHECK(probe.err == "error: " + message + "\n");
}
