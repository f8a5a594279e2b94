#include "engine/run/reload_guard.hpp"

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

struct Changes {
  std::vector<std::string> items;
  void compare(const char* name, double before, double after) {
    if (before != after) items.push_back(std::string(name) + " " + format_number(before) + " -> " + format_number(after));
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

// Each limit that would bound force less: a higher force, slew or threshold limit, a
// wider workspace, a shorter soft start. (The derived per-tick fields follow from these
// and the rate, which cannot change.)
void compare_safety(const SafetyConfig& a, const SafetyConfig& b, Changes* c) {
  const auto looser = [c](const char* name, double before, double after, bool loosened) {
    if (loosened) c->items.push_back(std::string(name) + " " + format_number(before) + " -> " + format_number(after));
  };
  looser("max_force_N", a.max_force_N, b.max_force_N, b.max_force_N > a.max_force_N);
  looser("slew_limit_N_per_s", a.slew_limit_N_per_s, b.slew_limit_N_per_s, b.slew_limit_N_per_s > a.slew_limit_N_per_s);
  looser("workspace_min_m", a.workspace_min_m, b.workspace_min_m, b.workspace_min_m < a.workspace_min_m);
  looser("workspace_max_m", a.workspace_max_m, b.workspace_max_m, b.workspace_max_m > a.workspace_max_m);
  looser("soft_start_s", a.soft_start_s, b.soft_start_s, b.soft_start_s < a.soft_start_s);
  looser("soft_start_threshold_N", a.soft_start_threshold_N, b.soft_start_threshold_N,
         b.soft_start_threshold_N > a.soft_start_threshold_N);
}

}  // namespace

std::string reload_refusal(const Scene& running, const Scene& next) {
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

}  // namespace hapscene
