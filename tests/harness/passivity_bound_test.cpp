// The passivity bound validate prints and reports: the smaller of Colgate and Schenkel's
// 2 b / T and Abbott and Okamura's 2 f_c / D, named. 2b/T binds at 1 kHz on the Hapkit
// profile (800 N/m against 16 kN/m); above about 20 kHz 2fc/D does.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/devices/kinematics.hpp"
#include "engine/harness/report.hpp"
#include "engine/harness/validate.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {
double count_m(const DeviceProfile& profile) {
  return std::abs(counts_to_position_m(profile, 1.0) - counts_to_position_m(profile, 0.0));
}

ValidationReport held_wall_at(const std::string& rate) {
  const Scene scene = test::scene_from(R"({"rate_hz": )" + rate +
                                       R"(, "effects": [{"type": "wall", "position": "10 mm", "stiffness": 500, "solid": "above"}]})");
  return validate_scene(scene, {ScenarioKind::hold}, HarnessOptions{});
}
}  // namespace

TEST_CASE("passivity bound: 2b/T binds at 1 kHz") {
  const ValidationReport report = held_wall_at("1000");
  CHECK(std::string(report.passivity_bound_name) == "2b/T");
  CHECK(report.passivity_bound_N_per_m == doctest::Approx(800.0));
  CHECK(format_report_table(report).find("1000 Hz, passivity bound 2b/T = 800 N/m,") != std::string::npos);
}

TEST_CASE("passivity bound: 2fc/D binds at 50 kHz, where 2b/T (40 kN/m) would overstate it") {
  const ValidationReport report = held_wall_at("50000");
  const Scene scene = test::scene_from(R"({"effects": [{"type": "damper", "damping": 1}]})");
  const double expected_N_per_m = 2.0 * scene.device.plant.coulomb_N / count_m(scene.device);
  CHECK(expected_N_per_m == doctest::Approx(16311.0).epsilon(0.001));
  CHECK(std::string(report.passivity_bound_name) == "2fc/D");
  CHECK(report.passivity_bound_N_per_m == doctest::Approx(expected_N_per_m));
  CHECK(format_report_table(report).find("50000 Hz, passivity bound 2fc/D = 16311 N/m,") != std::string::npos);
  const nlohmann::json json = report_to_json(report);
  CHECK(json["scene"]["passivity_bound"] == "2fc/D");
  CHECK(json["scene"]["passivity_bound_N_per_m"] == doctest::Approx(expected_N_per_m));
}

TEST_CASE("passivity bound: the crossover, and a frictionless device has no passive wall under quantization") {
  DeviceProfile device = test::scene_from(R"({"effects": [{"type": "damper", "damping": 1}]})").device;
  const double crossover_Hz = device.plant.coulomb_N / count_m(device) / device.plant.viscous_N_s_per_m;
  CHECK(crossover_Hz == doctest::Approx(20389.0).epsilon(0.001));
  CHECK(std::string(passivity_bound(device, 1.0 / (0.99 * crossover_Hz)).name) == "2b/T");
  CHECK(std::string(passivity_bound(device, 1.0 / (1.01 * crossover_Hz)).name) == "2fc/D");
  device.plant.coulomb_N = 0.0;
  CHECK(passivity_bound(device, 0.001).N_per_m == 0.0);
  CHECK(std::string(passivity_bound(device, 0.001).name) == "2fc/D");
}
