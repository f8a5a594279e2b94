// 2-DOF device profiles as data: the shipped ones load by name and by path, each loader
// refuses the other kind naming it, errors are located, and every shipped workspace is
// reachable, inside the joint stops and away from singular poses.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/base/units.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/devices/profile.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/devices/planar_support.hpp"
#include "tests/support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

nlohmann::json shipped_json(const std::string& name) {
  return nlohmann::json::parse(test::slurp_file(test::source_path("environments/devices/" + name + ".json")));
}

std::string planar_error(const nlohmann::json& j) {
  return test::input_error_of([&] { parse_planar_profile(j.dump(), "x.json"); });
}

// Where a profile's joints are at a reading of zero (encoders), mid-period (MR sensors)
// or the board's reference pose (angle sensors): a start for the inverse kinematics.
Vec2 start_angles(const PlanarProfile& profile) {
  Vec2 q{};
  for (int i = 0; i < 2; ++i) {
    const PlanarSensor& s = profile.joints[static_cast<std::size_t>(i)].sensor;
    if (s.kind == PlanarSensorKind::angle) q[i] = s.board_offset_rad + s.offset_rad;
    if (s.kind == PlanarSensorKind::encoder) q[i] = s.offset_rad;
    if (s.kind == PlanarSensorKind::mr) {
      q[i] = (s.min_counts + s.span_counts / 2.0) * s.counts_to_deg_slope * kDeg + s.offset_rad;
    }
  }
  q[1] += profile.coupling * q[0];
  return q;
}

}  // namespace

TEST_CASE("planar profile: every shipped profile loads by name and by path") {
  for (const std::string& name : test::shipped_planar_profiles()) {
    CAPTURE(name);
    const PlanarProfile by_name = load_planar_profile(name, ".");
    CHECK(by_name.name == name);
    const PlanarProfile by_path = load_planar_profile("devices/" + name + ".json", test::source_path("environments"));
    CHECK(by_path.name == name);
    CHECK(profile_kind_of(test::slurp_file(test::source_path("environments/devices/" + name + ".json"))) == "planar");
  }
  CHECK(profile_kind_of(test::slurp_file(test::source_path("environments/devices/hapkit3.json"))) == "capstan");
  CHECK(profile_kind_of("not json").empty());
}

TEST_CASE("planar profile: the Haplink's course constants") {
  const PlanarProfile p = load_planar_profile("haplink", ".");
  CHECK(p.linkage.family == LinkageFamily::serial_2r);
  CHECK(p.linkage.serial.link_a_m == doctest::Approx(0.087));
  CHECK(p.linkage.serial.link_b_m == doctest::Approx(0.100));
  CHECK(p.linkage.serial.offset_a_rad == doctest::Approx(0.8727));
  CHECK(p.linkage.serial.offset_b_rad == doctest::Approx(-1.4));
  for (const PlanarJoint& joint : p.joints) {
    CHECK(joint.sensor.kind == PlanarSensorKind::encoder);
    CHECK(joint.sensor.counts_per_revolution == 48.0);
    CHECK(joint.transmission_ratio == doctest::Approx(5.5 / 72.0));
    CHECK(joint.drive.law == PlanarDriveLaw::linear);
    CHECK(joint.drive.duty_per_N_m == doctest::Approx(65.13));
  }
  CHECK(p.coupling == doctest::Approx(5.5 / 72.0));
  CHECK(p.home_m[0] == doctest::Approx(-0.016327652));
  CHECK(p.home_m[1] == doctest::Approx(0.142337051));
}

TEST_CASE("planar profile: the 2DIY profiles carry the published lengths, offsets and counts") {
  struct Expected {
    const char* name;
    double l, big_l, d, offset_1_deg, offset_2_deg, counts;
    bool ccw_1, ccw_2;
  };
  for (const Expected& e : {Expected{"haply2diy_v1", 0.05, 0.07, 0.02, 180, 0, 13824, false, false},
                            Expected{"haply2diy_v2", 0.07, 0.09, 0.0, 241, -61, 10752, true, false},
                            Expected{"haply2diy_v3", 0.07, 0.09, 0.038, 168, 12, 4880, true, true}}) {
    CAPTURE(e.name);
    const PlanarProfile p = load_planar_profile(e.name, ".");
    const FiveBarGeometry& g = p.linkage.five_bar;
    CHECK(p.linkage.family == LinkageFamily::five_bar);
    CHECK(g.proximal_1_m == doctest::Approx(e.l));
    CHECK(g.proximal_2_m == doctest::Approx(e.l));
    CHECK(g.distal_1_m == doctest::Approx(e.big_l));
    CHECK(g.distal_2_m == doctest::Approx(e.big_l));
    CHECK(g.base_2_m[0] - g.base_1_m[0] == doctest::Approx(e.d));
    CHECK(p.joints[0].sensor.board_offset_rad == doctest::Approx(e.offset_1_deg * kDeg));
    CHECK(p.joints[1].sensor.board_offset_rad == doctest::Approx(e.offset_2_deg * kDeg));
    CHECK(p.joints[0].sensor.board_counter_clockwise == e.ccw_1);
    CHECK(p.joints[1].sensor.board_counter_clockwise == e.ccw_2);
    for (const PlanarJoint& joint : p.joints) {
      CHECK(joint.sensor.counts_per_revolution == e.counts);
      CHECK(joint.drive.law == PlanarDriveLaw::torque);
      CHECK(joint.drive.torque_max_N_m == doctest::Approx(0.123));
      CHECK(joint.transmission_ratio == 1.0);
    }
  }
}

TEST_CASE("planar profile: each shipped workspace is reachable, inside the stops, away from singularities") {
  for (const std::string& name : test::shipped_planar_profiles()) {
    CAPTURE(name);
    const PlanarProfile p = load_planar_profile(name, ".");
    const auto home = test::inverse_kinematics(p.linkage, p.home_m, start_angles(p));
    REQUIRE(home.has_value());
    const PlanarWorkspace& w = p.limits.workspace;
    REQUIRE(w.is_box);
    const int n = 12;
    double worst_condition = 0.0;
    for (int ix = 0; ix <= n; ++ix) {
      Vec2 q = *home;  // each column starts from home, then follows its points
      for (int iy = 0; iy <= n; ++iy) {
        const Vec2 target{{w.box_min_m[0] + (w.box_max_m[0] - w.box_min_m[0]) * ix / n,
                           w.box_min_m[1] + (w.box_max_m[1] - w.box_min_m[1]) * iy / n}};
        CAPTURE(target[0]);
        CAPTURE(target[1]);
        const auto reached = test::inverse_kinematics(p.linkage, target, q);
        REQUIRE(reached.has_value());
        q = *reached;
        const Vec2 sensed{{q[0], q[1] - p.coupling * q[0]}};
        for (int joint = 0; joint < 2; ++joint) {
          CAPTURE(joint);
          CHECK(sensed[joint] > p.plant.end_stops_rad[static_cast<std::size_t>(joint)][0]);
          CHECK(sensed[joint] < p.plant.end_stops_rad[static_cast<std::size_t>(joint)][1]);
        }
        const double condition = condition_number(solve_linkage(p.linkage, q).jacobian);
        worst_condition = std::fmax(worst_condition, condition);
      }
    }
    // Measured: haplink 8.7, hapkit_pantograph 2.6, haply2diy_v1 1.6, v2 1.7, v3 3.0.
    CHECK(worst_condition < p.limits.condition_limit);
  }
}

TEST_CASE("planar profile: each loader refuses the other kind, saying so") {
  CHECK(test::input_error_of([] { load_device_profile("haplink", "."); }) ==
        "environments/devices/haplink.json: /kind: a 2-DOF (planar) profile: a 1-DOF device needs a 1-DOF "
        "profile such as \"hapkit3\"");
  CHECK(test::input_error_of([] { load_planar_profile("hapkit3", "."); }) ==
        "environments/devices/hapkit3.json: a 1-DOF profile (no \"kind\": \"planar\"): a 2-DOF device needs a "
        "planar profile such as \"haplink\" or \"haply2diy_v3\"");
  nlohmann::json capstan = shipped_json("hapkit3");
  capstan["kind"] = "capstan";
  CHECK(parse_device_profile(capstan.dump(), "x.json").name == "hapkit3");  // 1-DOF may say so
  CHECK(planar_error(capstan) ==
        "x.json: /kind: a 1-DOF profile (\"capstan\"): a 2-DOF device needs a planar profile such as "
        "\"haplink\" or \"haply2diy_v3\"");
  capstan["kind"] = "planer";
  CHECK(test::input_error_of([&] { parse_device_profile(capstan.dump(), "x.json"); }) ==
        "x.json: /kind: \"planer\" is not one of \"capstan\", \"planar\" (did you mean \"planar\"?)");
  // Unknown names: each loader suggests names of its own kind.
  CHECK(test::input_error_of([] { load_planar_profile("haplnk", "."); }) ==
        "unknown planar device profile \"haplnk\" (did you mean \"haplink\"?)");
  CHECK(test::input_error_of([] { load_planar_profile("hapkit", "."); }).find("hapkit3") == std::string::npos);
  CHECK(test::input_error_of([] { load_device_profile("haplnk", "."); }).find("haplink") == std::string::npos);
}

TEST_CASE("planar profile: errors name the file and the JSON pointer") {
  const nlohmann::json good = shipped_json("haplink");
  auto with = [&](const nlohmann::json::json_pointer& at, const nlohmann::json& value) {
    nlohmann::json j = good;
    j[at] = value;
    return planar_error(j);
  };
  using P = nlohmann::json::json_pointer;
  CHECK(with(P("/kinematics/link_a"), "2 m") == "x.json: /kinematics/link_a: must be in [0.0001, 1] m, got 2 m");
  CHECK(with(P("/kinematics/offset_a"), "10 mm") ==
        "x.json: /kinematics/offset_a: expected an angle (rad), got a length (\"10 mm\")");
  CHECK(with(P("/kinematics/family"), "serial") ==
        "x.json: /kinematics/family: \"serial\" is not one of \"serial_2r\", \"five_bar\" (did you mean \"serial_2r\"?)");
  CHECK(with(P("/joints/1/drive/duty_per_N_m"), 0) == "x.json: /joints/1/drive/duty_per_N_m: must be > 0, got 0");
  CHECK(with(P("/joints/0/drive/spare"), 1) == "x.json: /joints/0/drive/spare: unknown key \"spare\"");
  CHECK(with(P("/joints/0/sensor/counts_per_revolution"), 0) ==
        "x.json: /joints/0/sensor/counts_per_revolution: must be in [1, 16777216], got 0");
  CHECK(with(P("/coupling"), 11) == "x.json: /coupling: must be in [-10, 10], got 11");
  CHECK(with(P("/home/1"), "2 km") == "x.json: /home/1: unknown unit \"km\" (did you mean \"m\"?)");
  CHECK(with(P("/home/1"), "2000 m") == "x.json: /home/1: must be in [-1000, 1000] m, got 2000 m");
  CHECK(with(P("/home"), nlohmann::json::array({"0 mm", "0 mm"})) == "x.json: /home: must lie inside /limits/workspace");
  CHECK(with(P("/limits/condition_limit"), 1) == "x.json: /limits/condition_limit: must be in (1, 1000000], got 1");
  CHECK(with(P("/limits/workspace/box/min/0"), "1 m") ==
        "x.json: /limits/workspace/box: min must be below max in x and in y");
  CHECK(with(P("/plant/viscous/1"), "-1 N*m*s/rad") == "x.json: /plant/viscous/1: must be >= 0, got -1 N*m*s/rad");
  CHECK(with(P("/plant/end_stops/0"), nlohmann::json::array({"1 rad", "0 rad"})) ==
        "x.json: /plant/end_stops/0: low must be below high");
  CHECK(with(P("/plant/links"), nlohmann::json::array()) ==
        "x.json: /plant/links: expected an array of two links (link a, link b) for a serial_2r arm, got an array of 0");
  CHECK(with(P("/joints"), nlohmann::json::array()) ==
        "x.json: /joints: expected an array of two joints (joint 1, joint 2), got an array of 0");
  CHECK(with(P("/frame"), "up") == "x.json: /frame: expected an object, got string");
  {
    nlohmann::json j = good;
    j["joints"][0].erase("sector_radius");
    CHECK(planar_error(j) == "x.json: /joints/0/pulley_radius: a capstan needs both \"pulley_radius\" and "
                             "\"sector_radius\" (a direct drive gives neither)");
  }
  {
    nlohmann::json j = good;
    j["spare"] = 1;
    CHECK(planar_error(j) == "x.json: /spare: unknown key \"spare\" (did you mean \"name\"?)");
  }
  {
    nlohmann::json j = good;
    j["limits"]["workspace"] = {{"polygon", nlohmann::json::array({nlohmann::json::array({"0 mm", "100 mm"}), nlohmann::json::array({"10 mm", "100 mm"})})}};
    CHECK(planar_error(j) == "x.json: /limits/workspace/polygon: needs 3 to 1024 points, got 2");
    j["limits"]["workspace"] = {{"polygon", {{0, 0.1}, {0.01, 0.1}, {0.02, 0.1}}}};
    CHECK(planar_error(j) == "x.json: /limits/workspace/polygon: encloses no area");
    // Edges that cross: refused, naming them (the points enclose a non-zero signed area).
    j["limits"]["workspace"] = {{"polygon", {{-0.07, 0.09}, {0.03, 0.09}, {-0.07, 0.19}, {0.05, 0.19}}}};
    CHECK(planar_error(j) == "x.json: /limits/workspace/polygon: edges 1 (points 1 to 2) and 3 (points 3 to 0) cross "
                             "or touch: the outline must not intersect itself");
    j["limits"]["workspace"] = nlohmann::json::object();
    CHECK(planar_error(j) == "x.json: /limits/workspace: give exactly one of \"box\" and \"polygon\"");
  }
}

TEST_CASE("planar profile: a polygon workspace") {
  nlohmann::json j = shipped_json("haplink");
  j["limits"]["workspace"] = {{"polygon", nlohmann::json::array({nlohmann::json::array({"-70 mm", "90 mm"}), nlohmann::json::array({"40 mm", "90 mm"}), nlohmann::json::array({"-16 mm", "165 mm"})})}};
  const PlanarProfile p = parse_planar_profile(j.dump(), "x.json");
  CHECK_FALSE(p.limits.workspace.is_box);
  CHECK(workspace_contains(p.limits.workspace, Vec2{{-0.016, 0.12}}));
  CHECK_FALSE(workspace_contains(p.limits.workspace, Vec2{{0.035, 0.16}}));
  CHECK_FALSE(workspace_contains(p.limits.workspace, Vec2{{-0.016, 0.08}}));
}

TEST_CASE("planar profile: a 1-DOF environment naming a planar device is refused, saying why") {
  CHECK(test::load_error(R"({"device": "haplink", "effects": []})") ==
        "test.json: /device: \"haplink\" is a 2-DOF (planar) profile: this command takes 1-DOF scenes only so far "
        "(2-DOF scenes: probe, run, plot and validate)");
  // The 1-DOF profile loader itself says what kind of profile it needs.
  CHECK_THROWS_WITH(load_device_profile("haplink", "."),
                    "environments/devices/haplink.json: /kind: a 2-DOF (planar) profile: a 1-DOF device needs a "
                    "1-DOF profile such as \"hapkit3\"");
  // 1-DOF names are still suggested for a misspelt 1-DOF name.
  CHECK(test::load_error(R"({"device": "hapkit2", "effects": []})") ==
        "test.json: /device: unknown device profile \"hapkit2\" (did you mean \"hapkit3\"?)");
}

TEST_CASE("planar profile: the joint-space units") {
  CHECK(parse_quantity_as("168 deg", Quantity::angle_rad).value_si == doctest::Approx(168.0 * kDeg).epsilon(1e-15));
  CHECK(parse_quantity_as("-1.4 rad", Quantity::angle_rad).value_si == -1.4);
  CHECK(parse_quantity_as("0.123 N*m", Quantity::torque_N_m).value_si == doctest::Approx(0.123));
  CHECK(parse_quantity_as("15 mN m", Quantity::torque_N_m).value_si == doctest::Approx(0.015));
  CHECK(parse_quantity_as("2 g*cm^2", Quantity::inertia_kg_m2).value_si == doctest::Approx(2e-7));
  CHECK(parse_quantity_as("1.7 mN*m*s/rad", Quantity::rotational_damping_N_m_s_per_rad).value_si == doctest::Approx(1.7e-3));
  CHECK(parse_quantity_as("86 N*m/rad", Quantity::rotational_stiffness_N_m_per_rad).value_si == 86.0);
  // Articles in messages: "an angle", and the older quantities unchanged ("a length").
  CHECK(parse_quantity_as("3 mm", Quantity::angle_rad).error == "expected an angle (rad), got a length (\"3 mm\")");
  CHECK(parse_quantity_as("3 deg", Quantity::length_m).error == "expected a length (m), got an angle (\"3 deg\")");
}

}  // namespace HAPSCENE_TEST_FILE
