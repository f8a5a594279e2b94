#include "engine/run/reload_guard.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "engine/base/object_reader.hpp"

namespace hapscene {
namespace {

// Every field of a profile is listed below; a new field must be added there too.
static_assert(sizeof(SensorModel) == sizeof(double) /* kind, padded */ + 2 * sizeof(double) + 3 * sizeof(std::int32_t) + 4,
              "SensorModel changed: update reload_refusal's list");
static_assert(sizeof(DriveModel) == 5 * sizeof(double) + sizeof(double) /* duty_law, padded */ + 2 * sizeof(int),
              "DriveModel changed: update reload_refusal's list");
static_assert(sizeof(DeviceLimits) == 8 * sizeof(double), "DeviceLimits changed: update reload_refusal's list");
static_assert(sizeof(PlantModel) == 7 * sizeof(double), "PlantModel changed: update reload_refusal's list");
static_assert(sizeof(SafetyConfig) == 8 * sizeof(double), "SafetyConfig changed: update reload_refusal's list");

// The same for a planar profile (sizes on x86-64, where the suite runs).
static_assert(sizeof(PlanarSensor) == 72, "PlanarSensor changed: update compare_profiles (planar)");
static_assert(sizeof(PlanarDrive) == 56, "PlanarDrive changed: update compare_profiles (planar)");
static_assert(sizeof(PlanarJoint) == 144, "PlanarJoint changed: update compare_profiles (planar)");
static_assert(sizeof(SerialArmGeometry) == 48 && sizeof(FiveBarGeometry) == 72 && sizeof(Linkage) == 128,
              "a linkage geometry changed: update compare_profiles (planar)");
static_assert(sizeof(PlanarWorkspace) == 64 && sizeof(PlanarLimits) == 104,
              "PlanarLimits changed: update compare_profiles (planar)");
static_assert(sizeof(PlanarLinkMass) == 24 && sizeof(PlanarPlantEstimates) == 208,
              "PlanarPlantEstimates changed: update compare_profiles (planar)");
// (name and source name the profile in messages: not compared.)
static_assert(sizeof(PlanarProfile) == 976, "PlanarProfile changed: update compare_profiles (planar)");

struct Changes {
  std::vector<std::string> items;
  void compare(const char* name, double before, double after) {
    if (before != after) items.push_back(std::string(name) + " " + format_number(before) + " -> " + format_number(after));
  }
  void compare(const std::string& name, const Vec2& before, const Vec2& after) {
    compare((name + ".x").c_str(), before[0], after[0]);
    compare((name + ".y").c_str(), before[1], after[1]);
  }
  void compare_text(const char* name, const std::string& before, const std::string& after) {
    if (before != after) items.push_back(std::string(name) + " changed");
  }
  std::string joined() const {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
    return out;
  }
};

// Every number of the profile.
void compare_profiles(const DeviceProfile& a, const DeviceProfile& b, Changes* c) {
  c->compare("sensor.type (0 mr, 1 encoder)", static_cast<int>(a.sensor.kind), static_cast<int>(b.sensor.kind));
  c->compare("sensor.counts_to_deg_slope", a.sensor.counts_to_deg_slope, b.sensor.counts_to_deg_slope);
  c->compare("sensor.counts_to_deg_offset", a.sensor.counts_to_deg_offset, b.sensor.counts_to_deg_offset);
  c->compare("sensor.min_counts", a.sensor.min_counts, b.sensor.min_counts);
  c->compare("sensor.span_counts", a.sensor.span_counts, b.sensor.span_counts);
  c->compare("sensor.flip_threshold_counts", a.sensor.flip_threshold_counts, b.sensor.flip_threshold_counts);
  c->compare("drive.handle_radius_m", a.drive.handle_radius_m, b.drive.handle_radius_m);
  c->compare("drive.pulley_radius_m", a.drive.pulley_radius_m, b.drive.pulley_radius_m);
  c->compare("drive.sector_radius_m", a.drive.sector_radius_m, b.drive.sector_radius_m);
  c->compare("drive.duty_law (0 sqrt, 1 linear)", static_cast<int>(a.drive.duty_law), static_cast<int>(b.drive.duty_law));
  c->compare("drive.motor_constant_N_m", a.drive.motor_constant_N_m, b.drive.motor_constant_N_m);
  c->compare("drive.duty_max", a.drive.duty_max, b.drive.duty_max);
  c->compare("drive.direction_sign", a.drive.direction_sign, b.drive.direction_sign);
  c->compare("drive.pwm_levels", a.drive.pwm_levels, b.drive.pwm_levels);
  c->compare("limits.max_force_N", a.limits.max_force_N, b.limits.max_force_N);
  c->compare("limits.slew_limit_N_per_s", a.limits.slew_limit_N_per_s, b.limits.slew_limit_N_per_s);
  c->compare("limits.workspace_min_m", a.limits.workspace_min_m, b.limits.workspace_min_m);
  c->compare("limits.workspace_max_m", a.limits.workspace_max_m, b.limits.workspace_max_m);
  c->compare("limits.soft_start_s", a.limits.soft_start_s, b.limits.soft_start_s);
  c->compare("limits.soft_start_threshold_N", a.limits.soft_start_threshold_N, b.limits.soft_start_threshold_N);
  c->compare("limits.slip_force_N", a.limits.slip_force_N, b.limits.slip_force_N);
  c->compare("limits.slip_step_N", a.limits.slip_step_N, b.limits.slip_step_N);
  c->compare("plant.mass_kg", a.plant.mass_kg, b.plant.mass_kg);
  c->compare("plant.viscous_N_s_per_m", a.plant.viscous_N_s_per_m, b.plant.viscous_N_s_per_m);
  c->compare("plant.coulomb_N", a.plant.coulomb_N, b.plant.coulomb_N);
  c->compare("plant.end_stop_min_m", a.plant.end_stop_min_m, b.plant.end_stop_min_m);
  c->compare("plant.end_stop_max_m", a.plant.end_stop_max_m, b.plant.end_stop_max_m);
  c->compare("plant.end_stop_stiffness_N_per_m", a.plant.end_stop_stiffness_N_per_m, b.plant.end_stop_stiffness_N_per_m);
  c->compare("plant.sensor_noise_counts", a.plant.sensor_noise_counts, b.plant.sensor_noise_counts);
}

// Every field of a planar profile.
void compare_profiles(const PlanarProfile& a, const PlanarProfile& b, Changes* c) {
  c->compare_text("frame", a.frame.origin + a.frame.x_axis + a.frame.y_axis, b.frame.origin + b.frame.x_axis + b.frame.y_axis);
  c->compare("linkage.family (0 serial_2r, 1 five_bar)", static_cast<int>(a.linkage.family), static_cast<int>(b.linkage.family));
  const SerialArmGeometry& sa = a.linkage.serial;
  const SerialArmGeometry& sb = b.linkage.serial;
  c->compare("linkage.base_m", sa.base_m, sb.base_m);
  c->compare("linkage.link_a_m", sa.link_a_m, sb.link_a_m);
  c->compare("linkage.link_b_m", sa.link_b_m, sb.link_b_m);
  c->compare("linkage.offset_a_rad", sa.offset_a_rad, sb.offset_a_rad);
  c->compare("linkage.offset_b_rad", sa.offset_b_rad, sb.offset_b_rad);
  const FiveBarGeometry& fa = a.linkage.five_bar;
  const FiveBarGeometry& fb = b.linkage.five_bar;
  c->compare("linkage.base_1_m", fa.base_1_m, fb.base_1_m);
  c->compare("linkage.base_2_m", fa.base_2_m, fb.base_2_m);
  c->compare("linkage.proximal_1_m", fa.proximal_1_m, fb.proximal_1_m);
  c->compare("linkage.proximal_2_m", fa.proximal_2_m, fb.proximal_2_m);
  c->compare("linkage.distal_1_m", fa.distal_1_m, fb.distal_1_m);
  c->compare("linkage.distal_2_m", fa.distal_2_m, fb.distal_2_m);
  c->compare("linkage.assembly_sign", fa.assembly_sign, fb.assembly_sign);
  for (std::size_t j = 0; j < 2; ++j) {
    const std::string at = "joints[" + std::to_string(j + 1) + "].";
    const auto number = [&](const char* name, double before, double after) { c->compare((at + name).c_str(), before, after); };
    const PlanarSensor& ra = a.joints[j].sensor;
    const PlanarSensor& rb = b.joints[j].sensor;
    number("sensor.type (0 mr, 1 encoder, 2 angle)", static_cast<int>(ra.kind), static_cast<int>(rb.kind));
    number("sensor.offset_rad", ra.offset_rad, rb.offset_rad);
    number("sensor.counts_to_deg_slope", ra.counts_to_deg_slope, rb.counts_to_deg_slope);
    number("sensor.min_counts", ra.min_counts, rb.min_counts);
    number("sensor.span_counts", ra.span_counts, rb.span_counts);
    number("sensor.flip_threshold_counts", ra.flip_threshold_counts, rb.flip_threshold_counts);
    number("sensor.counts_per_revolution", ra.counts_per_revolution, rb.counts_per_revolution);
    number("sensor.direction_sign", ra.direction_sign, rb.direction_sign);
    number("sensor.board_offset_rad", ra.board_offset_rad, rb.board_offset_rad);
    number("sensor.board_counter_clockwise", ra.board_counter_clockwise, rb.board_counter_clockwise);
    number("transmission_ratio", a.joints[j].transmission_ratio, b.joints[j].transmission_ratio);
    number("board_port", a.joints[j].board_port, b.joints[j].board_port);
    const PlanarDrive& da = a.joints[j].drive;
    const PlanarDrive& db = b.joints[j].drive;
    number("drive.law (0 sqrt, 1 linear, 2 torque)", static_cast<int>(da.law), static_cast<int>(db.law));
    number("drive.motor_constant_N_m", da.motor_constant_N_m, db.motor_constant_N_m);
    number("drive.duty_per_N_m", da.duty_per_N_m, db.duty_per_N_m);
    number("drive.duty_max", da.duty_max, db.duty_max);
    number("drive.torque_max_N_m", da.torque_max_N_m, db.torque_max_N_m);
    number("drive.direction_sign", da.direction_sign, db.direction_sign);
    number("drive.pwm_levels", da.pwm_levels, db.pwm_levels);
    number("drive.board_counter_clockwise", da.board_counter_clockwise, db.board_counter_clockwise);
  }
  c->compare("coupling", a.coupling, b.coupling);
  c->compare("home_m", a.home_m, b.home_m);
  // The boards were checked against these when the device opened.
  c->compare_text("board_serials[0]", a.board_serials[0], b.board_serials[0]);
  c->compare_text("board_serials[1]", a.board_serials[1], b.board_serials[1]);
  const PlanarLimits& la = a.limits;
  const PlanarLimits& lb = b.limits;
  c->compare("limits.max_force_N", la.max_force_N, lb.max_force_N);
  c->compare("limits.slew_limit_N_per_s", la.slew_limit_N_per_s, lb.slew_limit_N_per_s);
  c->compare("limits.soft_start_s", la.soft_start_s, lb.soft_start_s);
  c->compare("limits.soft_start_threshold_N", la.soft_start_threshold_N, lb.soft_start_threshold_N);
  c->compare("limits.condition_limit", la.condition_limit, lb.condition_limit);
  c->compare("limits.workspace (1 box, 0 polygon)", la.workspace.is_box, lb.workspace.is_box);
  c->compare("limits.workspace.min_m", la.workspace.box_min_m, lb.workspace.box_min_m);
  c->compare("limits.workspace.max_m", la.workspace.box_max_m, lb.workspace.box_max_m);
  const bool same_polygon =
      la.workspace.polygon_m.size() == lb.workspace.polygon_m.size() &&
      std::equal(la.workspace.polygon_m.begin(), la.workspace.polygon_m.end(), lb.workspace.polygon_m.begin(),
                 [](const Vec2& p, const Vec2& q) { return p[0] == q[0] && p[1] == q[1]; });
  if (!same_polygon) c->items.push_back("limits.workspace.polygon changed");
  const PlanarPlantEstimates& pa = a.plant;
  const PlanarPlantEstimates& pb = b.plant;
  for (std::size_t k = 0; k < pa.links.size(); ++k) {
    const std::string at = "plant.links[" + std::to_string(k + 1) + "].";
    c->compare((at + "mass_kg").c_str(), pa.links[k].mass_kg, pb.links[k].mass_kg);
    c->compare((at + "inertia_kg_m2").c_str(), pa.links[k].inertia_kg_m2, pb.links[k].inertia_kg_m2);
    c->compare((at + "center_of_mass_m").c_str(), pa.links[k].center_of_mass_m, pb.links[k].center_of_mass_m);
  }
  c->compare("plant.link_count", pa.link_count, pb.link_count);
  c->compare("plant.handle_mass_kg", pa.handle_mass_kg, pb.handle_mass_kg);
  c->compare("plant.rotor_inertia_kg_m2", pa.rotor_inertia_kg_m2, pb.rotor_inertia_kg_m2);
  c->compare("plant.viscous_N_m_s_per_rad", pa.viscous_N_m_s_per_rad, pb.viscous_N_m_s_per_rad);
  c->compare("plant.coulomb_N_m", pa.coulomb_N_m, pb.coulomb_N_m);
  for (std::size_t j = 0; j < 2; ++j) {
    const std::string at = "plant.end_stops_rad[" + std::to_string(j + 1) + "].";
    c->compare((at + "min").c_str(), pa.end_stops_rad[j][0], pb.end_stops_rad[j][0]);
    c->compare((at + "max").c_str(), pa.end_stops_rad[j][1], pb.end_stops_rad[j][1]);
  }
  c->compare("plant.end_stop_stiffness_N_m_per_rad", pa.end_stop_stiffness_N_m_per_rad, pb.end_stop_stiffness_N_m_per_rad);
  c->compare("plant.sensor_noise_counts", pa.sensor_noise_counts, pb.sensor_noise_counts);
}

// The name of a workspace bound's axis i ("workspace_min_m" with one axis, "workspace_min_m.y").
std::string axis_name(const char* name, int axes, int i) {
  return axes == 1 ? std::string(name) : std::string(name) + (i == 0 ? ".x" : i == 1 ? ".y" : ".z");
}

// Each limit that would bound force less: a higher force, slew or threshold limit, a
// wider workspace, a shorter soft start. (The derived per-tick fields follow from these
// and the rate, which cannot change.)
template <int N>
void compare_safety(const SafetyConfigOf<N>& a, const SafetyConfigOf<N>& b, Changes* c) {
  const auto looser = [c](const std::string& name, double before, double after, bool loosened) {
    if (loosened) c->items.push_back(name + " " + format_number(before) + " -> " + format_number(after));
  };
  looser("max_force_N", a.max_force_N, b.max_force_N, b.max_force_N > a.max_force_N);
  looser("slew_limit_N_per_s", a.slew_limit_N_per_s, b.slew_limit_N_per_s, b.slew_limit_N_per_s > a.slew_limit_N_per_s);
  // A workspace wider on any axis. (With more than one axis, a polygon workspace is the
  // device's, which cannot change, and a box an environment sets must lie within it:
  // comparing the bounding boxes is enough.)
  for (int i = 0; i < N; ++i) {
    const double min_a = component(a.workspace_min_m, i), min_b = component(b.workspace_min_m, i);
    const double max_a = component(a.workspace_max_m, i), max_b = component(b.workspace_max_m, i);
    looser(axis_name("workspace_min_m", N, i), min_a, min_b, min_b < min_a);
    looser(axis_name("workspace_max_m", N, i), max_a, max_b, max_b > max_a);
  }
  looser("soft_start_s", a.soft_start_s, b.soft_start_s, b.soft_start_s < a.soft_start_s);
  looser("soft_start_threshold_N", a.soft_start_threshold_N, b.soft_start_threshold_N,
         b.soft_start_threshold_N > a.soft_start_threshold_N);
}

template <int N>
std::string refusal_of(const SceneOf<N>& running, const SceneOf<N>& next) {
  std::vector<std::string> reasons;
  if (next.rate_hz != running.rate_hz) {
    reasons.push_back("rate_hz cannot change during a run (" + format_number(running.rate_hz) + " -> " +
                      format_number(next.rate_hz) + ")");
  }
  Changes device;
  if (next.device.name != running.device.name) {
    device.items.push_back("name \"" + running.device.name + "\" -> \"" + next.device.name + "\"");
  }
  compare_profiles(running.device, next.device, &device);
  if (!device.items.empty()) {
    reasons.push_back("the device cannot change during a run (profile " + device.joined() + ")");
  }
  Changes safety;
  compare_safety(running.safety, next.safety, &safety);
  if (!safety.items.empty()) {
    reasons.push_back("a reload cannot loosen a safety limit (" + safety.joined() +
                      "); restart the run to loosen one");
  }
  std::string out;
  for (const std::string& reason : reasons) out += (out.empty() ? "" : "; ") + reason;
  return out;
}

}  // namespace

std::string reload_refusal(const Scene& running, const Scene& next) { return refusal_of(running, next); }

std::string reload_refusal(const PlanarScene& running, const PlanarScene& next) { return refusal_of(running, next); }

}  // namespace hapscene
