#include "engine/devices/planar/planar_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/base/polygon.hpp"

namespace hapscene {
namespace {

// Ranges of the planar profile's own numbers, in the spirit of profile.cpp's: far wider
// than any desktop device, narrow enough that kinematics and the plant stay finite.
constexpr Range kLink_m{1e-4, 1.0};                       // 0.1 mm to 1 m
constexpr Range kAngle_rad{-62.83185307179586, 62.83185307179586};  // ten turns
constexpr Range kCoupling{-10.0, 10.0};
constexpr Range kDutyPerTorque_per_N_m{0.0, 1e6, true};
constexpr Range kTorqueClamp_N_m{0.0, 100.0, true};
constexpr Range kConditionLimit{1.0, 1e6, true};
constexpr Range kPartMass_kg{0.0, 100.0};               // a link or the handle (0: massless)
constexpr Range kInertia_kg_m2{0.0, 100.0};
constexpr Range kCenterOfMass_m{-1.0, 1.0};
constexpr Range kJointViscous_N_m_s_per_rad{0.0, 100.0};
constexpr Range kJointCoulomb_N_m{0.0, 100.0};
constexpr Range kJointStopStiffness_N_m_per_rad{0.0, 1e6, true};
constexpr long long kMaxCountsPerRevolution = 1LL << 24;
constexpr std::size_t kMaxWorkspacePolygonPoints = 1024;

// The array at `key` with exactly `count` entries (count 0: any size within [3, max]).
const nlohmann::json& array_at(ObjectReader& reader, std::string_view key, std::size_t count, std::string_view what) {
  const nlohmann::json* value = reader.get(key);
  if (value == nullptr) reader.fail_missing(key);
  if (!value->is_array() || (count != 0 && value->size() != count)) {
    reader.fail(key, "expected " + std::string(what) + ", got " +
                         (value->is_array() ? "an array of " + std::to_string(value->size()) : json_type_name(*value)));
  }
  return *value;
}

// An [x, y] pair of quantities; each component's errors carry ".../key/0" or ".../key/1",
// as ObjectReader::range does for its ends.
Vec2 vector_from(const ObjectReader& reader, const std::string& pointer, const nlohmann::json& value,
                 Quantity quantity, Range range) {
  if (!value.is_array() || value.size() != 2) {
    const ObjectReader at(nlohmann::json::object(), pointer, reader.file());
    at.fail("", "expected [x, y] as an array of two " + std::string(quantity_name(quantity)) +
                    " values, got " + json_type_name(value));
  }
  const nlohmann::json ends = nlohmann::json::object({{"0", value[0]}, {"1", value[1]}});
  ObjectReader holder(ends, pointer, reader.file());
  return Vec2{{holder.quantity("0", quantity, range), holder.quantity("1", quantity, range)}};
}

Vec2 vector_at(ObjectReader& reader, std::string_view key, Quantity quantity, Range range) {
  const nlohmann::json* value = reader.get(key);
  if (value == nullptr) reader.fail_missing(key);
  return vector_from(reader, reader.pointer_to(key), *value, quantity, range);
}

int sign_at(ObjectReader& reader, std::string_view key) {
  const int sign = static_cast<int>(reader.integer_or(key, -1, 1, 1));
  if (sign == 0) reader.fail(key, "must be 1 or -1");
  return sign;
}

// --- kinematics ---------------------------------------------------------------------

Linkage parse_kinematics(ObjectReader& reader) {
  Linkage linkage;
  const std::string family = reader.choice("family", {"serial_2r", "five_bar"});
  if (family == "serial_2r") {
    linkage.family = LinkageFamily::serial_2r;
    SerialArmGeometry& g = linkage.serial;
    g.base_m = reader.has("base") ? vector_at(reader, "base", Quantity::length_m, ranges::kPosition_m) : Vec2{};
    g.link_a_m = reader.quantity("link_a", Quantity::length_m, kLink_m);
    g.link_b_m = reader.quantity("link_b", Quantity::length_m, kLink_m);
    g.offset_a_rad = reader.quantity_or("offset_a", Quantity::angle_rad, 0.0, kAngle_rad);
    g.offset_b_rad = reader.quantity_or("offset_b", Quantity::angle_rad, 0.0, kAngle_rad);
  } else {
    linkage.family = LinkageFamily::five_bar;
    FiveBarGeometry& g = linkage.five_bar;
    g.base_1_m = vector_at(reader, "base_1", Quantity::length_m, ranges::kPosition_m);
    g.base_2_m = vector_at(reader, "base_2", Quantity::length_m, ranges::kPosition_m);
    g.proximal_1_m = reader.quantity("proximal_1", Quantity::length_m, kLink_m);
    g.proximal_2_m = reader.quantity("proximal_2", Quantity::length_m, kLink_m);
    g.distal_1_m = reader.quantity("distal_1", Quantity::length_m, kLink_m);
    g.distal_2_m = reader.quantity("distal_2", Quantity::length_m, kLink_m);
    g.assembly_sign = reader.choice("assembly", {"left", "right"}, "left") == "left" ? 1 : -1;
  }
  reader.finish();
  return linkage;
}

// --- joints -------------------------------------------------------------------------

PlanarSensor parse_planar_sensor(ObjectReader& reader) {
  PlanarSensor sensor;
  const std::string type = reader.choice("type", {"mr", "encoder", "angle"});
  if (type == "mr") {
    sensor.kind = PlanarSensorKind::mr;
    sensor.counts_to_deg_slope = reader.quantity("counts_to_deg_slope", Quantity::dimensionless);
    const double magnitude = std::abs(sensor.counts_to_deg_slope);
    if (magnitude < ranges::kDegPerCountMagnitude.min || magnitude > ranges::kDegPerCountMagnitude.max) {
      reader.fail("counts_to_deg_slope", "must be in [-10, -1e-06] or [1e-06, 10] (deg/count), got " +
                                             format_number(sensor.counts_to_deg_slope));
    }
    sensor.offset_rad = reader.quantity("counts_to_deg_offset", Quantity::dimensionless,
                                        Range{-3600.0, 3600.0}) * std::numbers::pi / 180.0;
    sensor.min_counts = static_cast<std::int32_t>(reader.integer("min_counts", 0, 65535));
    sensor.span_counts = static_cast<std::int32_t>(reader.integer("span_counts", 2, 65535));
    sensor.flip_threshold_counts = static_cast<std::int32_t>(
        reader.integer("flip_threshold_counts", 1, sensor.span_counts - 1));
  } else if (type == "encoder") {
    sensor.kind = PlanarSensorKind::encoder;
    sensor.counts_per_revolution =
        static_cast<double>(reader.integer("counts_per_revolution", 1, kMaxCountsPerRevolution));
    sensor.direction_sign = sign_at(reader, "direction_sign");
    sensor.offset_rad = reader.quantity_or("offset", Quantity::angle_rad, 0.0, kAngle_rad);
  } else {
    sensor.kind = PlanarSensorKind::angle;
    sensor.counts_per_revolution =
        static_cast<double>(reader.integer("counts_per_revolution", 1, kMaxCountsPerRevolution));
    sensor.board_offset_rad = reader.quantity("board_offset", Quantity::angle_rad, kAngle_rad);
    sensor.board_counter_clockwise = reader.choice("board_direction", {"cw", "ccw"}) == "ccw";
    sensor.offset_rad = reader.quantity_or("offset", Quantity::angle_rad, 0.0, kAngle_rad);
  }
  reader.finish();
  return sensor;
}

PlanarDrive parse_planar_drive(ObjectReader& reader) {
  PlanarDrive drive;
  const std::string law = reader.choice("law", {"sqrt", "linear", "torque"});
  if (law == "torque") {
    drive.law = PlanarDriveLaw::torque;
    drive.torque_max_N_m = reader.quantity("torque_max", Quantity::torque_N_m, kTorqueClamp_N_m);
    drive.board_counter_clockwise = reader.choice("board_direction", {"cw", "ccw"}) == "ccw";
  } else {
    if (law == "sqrt") {
      drive.law = PlanarDriveLaw::sqrt;
      drive.motor_constant_N_m = reader.quantity("motor_constant", Quantity::torque_N_m, ranges::kMotorConstant_N_m);
    } else {
      drive.law = PlanarDriveLaw::linear;
      drive.duty_per_N_m = reader.quantity("duty_per_N_m", Quantity::dimensionless, kDutyPerTorque_per_N_m);
    }
    drive.duty_max = reader.quantity("duty_max", Quantity::dimensionless, Bound::positive);
    if (drive.duty_max > 1.0) reader.fail("duty_max", "must be <= 1");
    drive.pwm_levels = static_cast<int>(reader.integer("pwm_levels", 1, 65535));
  }
  drive.direction_sign = sign_at(reader, "direction_sign");
  reader.finish();
  return drive;
}

PlanarJoint parse_joint(ObjectReader& reader, int number) {
  PlanarJoint joint;
  joint.sensor = reader.part("sensor", parse_planar_sensor);
  // A capstan: both radii or neither (a direct drive, ratio 1).
  const bool has_pulley = reader.has("pulley_radius");
  const bool has_sector = reader.has("sector_radius");
  if (has_pulley != has_sector) {
    reader.fail(has_pulley ? "pulley_radius" : "sector_radius",
                "a capstan needs both \"pulley_radius\" and \"sector_radius\" (a direct drive gives neither)");
  }
  if (has_pulley) {
    joint.transmission_ratio = reader.quantity("pulley_radius", Quantity::length_m, kLink_m) /
                               reader.quantity("sector_radius", Quantity::length_m, kLink_m);
  }
  joint.drive = reader.part("drive", parse_planar_drive);
  // Which board port: only a board that reports angles and takes torques has ports.
  const bool board_joint = joint.sensor.kind == PlanarSensorKind::angle && joint.drive.law == PlanarDriveLaw::torque;
  if (reader.has("board_port") && !board_joint) {
    reader.fail("board_port", "only a joint with an \"angle\" sensor and a \"torque\" drive is on a board port");
  }
  joint.board_port = static_cast<int>(reader.integer_or("board_port", 1, 4, number));
  reader.finish();
  return joint;
}

std::array<PlanarJoint, 2> parse_joints(ObjectReader& reader) {
  const nlohmann::json& joints = array_at(reader, "joints", 2, "an array of two joints (joint 1, joint 2)");
  std::array<PlanarJoint, 2> result{};
  for (std::size_t i = 0; i < 2; ++i) {
    ObjectReader joint_reader(joints[i], reader.pointer_to("joints") + "/" + std::to_string(i), reader.file());
    result[i] = parse_joint(joint_reader, static_cast<int>(i) + 1);
  }
  if (result[0].board_port == result[1].board_port && result[0].sensor.kind == PlanarSensorKind::angle) {
    ObjectReader second(joints[1], reader.pointer_to("joints") + "/1", reader.file());
    second.fail("board_port", "joint 1 is on board port " + std::to_string(result[0].board_port) +
                                  " already: each joint needs its own port");
  }
  return result;
}

// --- limits -------------------------------------------------------------------------

PlanarWorkspace parse_workspace(ObjectReader& reader) {
  PlanarWorkspace workspace;
  const bool has_box = reader.has("box");
  const bool has_polygon = reader.has("polygon");
  if (has_box == has_polygon) reader.fail("", "give exactly one of \"box\" and \"polygon\"");
  if (has_box) {
    workspace.is_box = true;
    reader.part("box", [&](ObjectReader& box) {
      workspace.box_min_m = vector_at(box, "min", Quantity::length_m, ranges::kPosition_m);
      workspace.box_max_m = vector_at(box, "max", Quantity::length_m, ranges::kPosition_m);
      if (!(workspace.box_min_m[0] < workspace.box_max_m[0]) || !(workspace.box_min_m[1] < workspace.box_max_m[1])) {
        box.fail("", "min must be below max in x and in y");
      }
      box.finish();
      return 0;
    });
  } else {
    workspace.is_box = false;
    const nlohmann::json& points = array_at(reader, "polygon", 0, "an array of [x, y] points");
    if (points.size() < 3 || points.size() > kMaxWorkspacePolygonPoints) {
      reader.fail("polygon", "needs 3 to " + std::to_string(kMaxWorkspacePolygonPoints) + " points, got " +
                                 std::to_string(points.size()));
    }
    double twice_area = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      workspace.polygon_m.push_back(vector_from(reader, reader.pointer_to("polygon") + "/" + std::to_string(i),
                                                points[i], Quantity::length_m, ranges::kPosition_m));
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      twice_area += cross(workspace.polygon_m[i], workspace.polygon_m[(i + 1) % points.size()]);
    }
    if (!(std::abs(twice_area) > 0.0)) reader.fail("polygon", "encloses no area");
    // A polygon that crosses itself has no one inside (the crossing-number test and a
    // person reading the points disagree): refused, naming the edges, as a shape's is.
    const std::string problem = simple_polygon_problem(workspace.polygon_m);
    if (!problem.empty()) reader.fail("polygon", problem);
  }
  reader.finish();
  return workspace;
}

PlanarLimits parse_planar_limits(ObjectReader& reader) {
  PlanarLimits limits;
  limits.max_force_N = reader.quantity("max_force", Quantity::force_N, ranges::kPositiveForce_N);
  limits.slew_limit_N_per_s =
      reader.quantity("slew_limit", Quantity::force_rate_N_per_s, ranges::kPositiveSlew_N_per_s);
  limits.soft_start_s = reader.quantity("soft_start", Quantity::time_s, ranges::kDuration_s);
  limits.soft_start_threshold_N = reader.quantity("soft_start_threshold", Quantity::force_N, ranges::kForce_N);
  limits.condition_limit = reader.quantity("condition_limit", Quantity::dimensionless, kConditionLimit);
  limits.workspace = reader.part("workspace", parse_workspace);
  reader.finish();
  return limits;
}

// --- plant --------------------------------------------------------------------------

PlanarLinkMass parse_link_mass(ObjectReader& reader) {
  PlanarLinkMass link;
  link.mass_kg = reader.quantity("mass", Quantity::mass_kg, kPartMass_kg);
  link.inertia_kg_m2 = reader.quantity("inertia", Quantity::inertia_kg_m2, kInertia_kg_m2);
  link.center_of_mass_m = reader.quantity("center_of_mass", Quantity::length_m, kCenterOfMass_m);
  reader.finish();
  return link;
}

PlanarPlantEstimates parse_planar_plant(ObjectReader& reader, LinkageFamily family) {
  PlanarPlantEstimates plant;
  plant.link_count = family == LinkageFamily::serial_2r ? 2 : 4;
  const char* links_expected = family == LinkageFamily::serial_2r
                                   ? "an array of two links (link a, link b) for a serial_2r arm"
                                   : "an array of four links (proximal 1, proximal 2, distal 1, distal 2) for a five_bar";
  const nlohmann::json& links = array_at(reader, "links", static_cast<std::size_t>(plant.link_count), links_expected);
  for (int i = 0; i < plant.link_count; ++i) {
    ObjectReader link_reader(links[static_cast<std::size_t>(i)], reader.pointer_to("links") + "/" + std::to_string(i),
                             reader.file());
    plant.links[static_cast<std::size_t>(i)] = parse_link_mass(link_reader);
  }
  plant.handle_mass_kg = reader.quantity("handle_mass", Quantity::mass_kg, kPartMass_kg);
  plant.rotor_inertia_kg_m2 = vector_at(reader, "rotor_inertia", Quantity::inertia_kg_m2, kInertia_kg_m2);
  plant.viscous_N_m_s_per_rad =
      vector_at(reader, "viscous", Quantity::rotational_damping_N_m_s_per_rad, kJointViscous_N_m_s_per_rad);
  plant.coulomb_N_m = vector_at(reader, "coulomb", Quantity::torque_N_m, kJointCoulomb_N_m);
  const nlohmann::json& stops = array_at(reader, "end_stops", 2, "an array of two joint ranges [[min, max], [min, max]]");
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string pointer = reader.pointer_to("end_stops") + "/" + std::to_string(i);
    plant.end_stops_rad[i] = vector_from(reader, pointer, stops[i], Quantity::angle_rad, kAngle_rad);
    if (!(plant.end_stops_rad[i][0] < plant.end_stops_rad[i][1])) {
      const ObjectReader at(nlohmann::json::object(), pointer, reader.file());
      at.fail("", "low must be below high");
    }
  }
  plant.end_stop_stiffness_N_m_per_rad = reader.quantity(
      "end_stop_stiffness", Quantity::rotational_stiffness_N_m_per_rad, kJointStopStiffness_N_m_per_rad);
  plant.sensor_noise_counts = reader.quantity("sensor_noise_counts", Quantity::dimensionless, ranges::kNoise_counts);
  reader.finish();
  return plant;
}

PlanarFrame parse_frame(ObjectReader& reader) {
  PlanarFrame frame;
  frame.origin = reader.string("origin");
  frame.x_axis = reader.string("x");
  frame.y_axis = reader.string("y");
  reader.finish();
  return frame;
}

}  // namespace

bool workspace_contains(const PlanarWorkspace& workspace, const Vec2& p_m) noexcept {
  if (workspace.is_box) {
    return p_m[0] >= workspace.box_min_m[0] && p_m[0] <= workspace.box_max_m[0] &&
           p_m[1] >= workspace.box_min_m[1] && p_m[1] <= workspace.box_max_m[1];
  }
  // Crossing number (even-odd rule).
  bool inside = false;
  const std::size_t n = workspace.polygon_m.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = workspace.polygon_m[i];
    const Vec2& b = workspace.polygon_m[j];
    if ((a[1] > p_m[1]) != (b[1] > p_m[1])) {
      const double x_cross = a[0] + (p_m[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (p_m[0] <= x_cross) inside = !inside;
    }
  }
  return inside;
}

void workspace_bounds(const PlanarWorkspace& workspace, Vec2* low_m, Vec2* high_m) noexcept {
  if (workspace.is_box || workspace.polygon_m.empty()) {
    *low_m = workspace.box_min_m;
    *high_m = workspace.box_max_m;
    return;
  }
  *low_m = workspace.polygon_m.front();
  *high_m = *low_m;
  for (const Vec2& p : workspace.polygon_m) {
    for (int i = 0; i < 2; ++i) {
      (*low_m)[i] = std::min((*low_m)[i], p[i]);
      (*high_m)[i] = std::max((*high_m)[i], p[i]);
    }
  }
}

std::string box_leaves_workspace(const PlanarWorkspace& workspace, const Vec2& low_m, const Vec2& high_m) {
  // A corner outside (for a box workspace, convex, that decides it).
  for (const Vec2& corner : {low_m, Vec2{{high_m[0], low_m[1]}}, high_m, Vec2{{low_m[0], high_m[1]}}}) {
    if (!workspace_contains(workspace, corner)) {
      return "its corner (" + format_number(corner[0]) + ", " + format_number(corner[1]) +
             ") m is outside it";
    }
  }
  // A polygon need not be convex: no edge of the polygon through the box's inside and
  // its centre inside put the whole box inside (the inside is connected, meets no edge).
  const std::size_t n = workspace.is_box ? 0 : workspace.polygon_m.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (segment_meets_box(workspace.polygon_m[i], workspace.polygon_m[j], low_m, high_m, BoxSides::open)) {
      return "edge " + std::to_string(i) + " (points " + std::to_string(i) + " to " + std::to_string(j) +
             ") of the device's polygon passes through the box";
    }
  }
  const Vec2 centre_m = (low_m + high_m) * 0.5;
  if (!workspace_contains(workspace, centre_m)) {
    return "its centre (" + format_number(centre_m[0]) + ", " + format_number(centre_m[1]) +
           ") m is outside it";
  }
  return {};
}

PlanarProfile parse_planar_profile(std::string_view json_text, const std::string& display_name) {
  const nlohmann::json root = parse_json_text(json_text, display_name);
  ObjectReader reader(root, "", display_name);
  PlanarProfile profile;
  // A 1-DOF profile says "capstan" or nothing: refuse it before any other key, so the
  // message names what is wrong rather than the first key a 1-DOF profile lacks.
  if (!reader.has("kind")) {
    reader.fail("", "a 1-DOF profile (no \"kind\": \"planar\"): a 2-DOF device needs a planar profile "
                    "such as \"haplink\" or \"haply2diy_v3\"");
  }
  const std::string kind = reader.choice("kind", {kPlanarProfileKind, kCapstanProfileKind});
  if (kind != kPlanarProfileKind) {
    reader.fail("kind", "a 1-DOF profile (\"" + kind + "\"): a 2-DOF device needs a planar profile "
                        "such as \"haplink\" or \"haply2diy_v3\"");
  }
  profile.name = reader.string("name");
  profile.source = display_name;
  reader.string_or("description", "");  // for people: checked to be text, not kept
  reader.string_or("note", "");
  profile.frame = reader.part("frame", parse_frame);
  profile.linkage = reader.part("kinematics", parse_kinematics);
  profile.joints = parse_joints(reader);
  profile.coupling = reader.quantity_or("coupling", Quantity::dimensionless, 0.0, kCoupling);
  profile.home_m = vector_at(reader, "home", Quantity::length_m, ranges::kPosition_m);
  profile.limits = reader.part("limits", parse_planar_limits);
  if (!workspace_contains(profile.limits.workspace, profile.home_m)) {
    reader.fail("home", "must lie inside /limits/workspace");
  }
  const LinkageFamily family = profile.linkage.family;
  profile.plant = reader.part("plant", [family](ObjectReader& plant) { return parse_planar_plant(plant, family); });
  if (const nlohmann::json* serials = reader.get("board_serials")) {
    const bool two_names = serials->is_array() && serials->size() == 2 && (*serials)[0].is_string() &&
                           (*serials)[1].is_string() && !(*serials)[0].get<std::string>().empty() &&
                           !(*serials)[1].get<std::string>().empty();
    if (!two_names) {
      reader.fail("board_serials", "must be two non-empty strings: the USB serial numbers of joint 1's and "
                                   "joint 2's boards (as `hapscene devices` lists them)");
    }
    if ((*serials)[0] == (*serials)[1]) reader.fail("board_serials", "names one board for both joints");
    profile.board_serials = {(*serials)[0].get<std::string>(), (*serials)[1].get<std::string>()};
  }
  reader.finish();
  return profile;
}

PlanarProfile load_planar_profile(const std::string& name_or_path, const std::string& base_dir) {
  const ProfileText text = find_profile_text(name_or_path, base_dir, /*planar=*/true);
  PlanarProfile profile = parse_planar_profile(text.json_text, text.display_name);
  profile.source = profile_source(name_or_path, text.display_name);
  return profile;
}

}  // namespace hapscene
