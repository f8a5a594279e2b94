#include "engine/devices/profile.hpp"

#include <cmath>
#include <filesystem>

#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/devices/builtin_profiles.hpp"

namespace hapscene {
namespace {

// Ranges of the profile's own numbers (docs/reference/devices.md); the
// shared ones are in physical_ranges.hpp. Each is far wider than any desktop haptic device
// and keeps the kinematics and the simulated plant finite.
constexpr Range kAngleOffset_deg{-3600.0, 3600.0};   // ten turns
constexpr Range kRadius_m{1e-4, 1.0};                // 0.1 mm to 1 m
constexpr Range kHandleMass_kg{1e-4, 100.0};         // 0.1 g to 100 kg at the handle

SensorModel parse_sensor(ObjectReader& reader) {
  SensorModel sensor;
  sensor.kind = reader.choice("type", {"mr", "encoder"}, "mr") == "encoder" ? SensorKind::encoder : SensorKind::mr;
  sensor.counts_to_deg_slope = reader.quantity("counts_to_deg_slope", Quantity::dimensionless);
  if (sensor.counts_to_deg_slope == 0.0) reader.fail("counts_to_deg_slope", "must not be 0");
  const double slope_magnitude = std::abs(sensor.counts_to_deg_slope);
  if (slope_magnitude < ranges::kDegPerCountMagnitude.min || slope_magnitude > ranges::kDegPerCountMagnitude.max) {
    reader.fail("counts_to_deg_slope", "must be in [-10, -1e-06] or [1e-06, 10] (deg/count), got " +
                                           format_number(sensor.counts_to_deg_slope));
  }
  sensor.counts_to_deg_offset =
      reader.quantity("counts_to_deg_offset", Quantity::dimensionless, kAngleOffset_deg);
  if (sensor.kind == SensorKind::encoder) {
    // A counter does not wrap: the keys of the MR sensor's period mean nothing for it.
    for (const char* key : {"min_counts", "span_counts", "flip_threshold_counts"}) {
      if (reader.has(key)) reader.fail(key, "not used by an encoder (its counts never wrap): remove it");
    }
  } else {
    sensor.min_counts = static_cast<std::int32_t>(reader.integer("min_counts", 0, 65535));
    sensor.span_counts = static_cast<std::int32_t>(reader.integer("span_counts", 2, 65535));
    sensor.flip_threshold_counts = static_cast<std::int32_t>(
        reader.integer("flip_threshold_counts", 1, sensor.span_counts - 1));
  }
  reader.finish();
  return sensor;
}

DriveModel parse_drive(ObjectReader& reader) {
  DriveModel drive;
  drive.handle_radius_m = reader.quantity("handle_radius", Quantity::length_m, kRadius_m);
  drive.pulley_radius_m = reader.quantity("pulley_radius", Quantity::length_m, kRadius_m);
  drive.sector_radius_m = reader.quantity("sector_radius", Quantity::length_m, kRadius_m);
  drive.duty_law = reader.choice("duty_law", {"sqrt", "linear"}, "sqrt") == "linear" ? DutyLaw::linear : DutyLaw::sqrt;
  drive.motor_constant_N_m =
      reader.quantity("motor_constant", Quantity::dimensionless, ranges::kMotorConstant_N_m);
  drive.duty_max = reader.quantity("duty_max", Quantity::dimensionless, Bound::positive);
  if (drive.duty_max > 1.0) reader.fail("duty_max", "must be <= 1");
  drive.direction_sign = static_cast<int>(reader.integer("direction_sign", -1, 1));
  if (drive.direction_sign == 0) reader.fail("direction_sign", "must be 1 or -1");
  drive.pwm_levels = static_cast<int>(reader.integer("pwm_levels", 1, 65535));
  reader.finish();
  return drive;
}

DeviceLimits parse_limits(ObjectReader& reader) {
  DeviceLimits limits;
  limits.max_force_N = reader.quantity("max_force", Quantity::force_N, ranges::kPositiveForce_N);
  limits.slew_limit_N_per_s =
      reader.quantity("slew_limit", Quantity::force_rate_N_per_s, ranges::kPositiveSlew_N_per_s);
  std::tie(limits.workspace_min_m, limits.workspace_max_m) =
      reader.range("workspace", Quantity::length_m, ranges::kPosition_m);
  limits.soft_start_s = reader.quantity("soft_start", Quantity::time_s, ranges::kDuration_s);
  limits.soft_start_threshold_N =
      reader.quantity("soft_start_threshold", Quantity::force_N, ranges::kForce_N);
  limits.slip_force_N =
      reader.quantity_or("slip_force", Quantity::force_N, kDefaultSlipForce_N, ranges::kPositiveForce_N);
  limits.slip_step_N =
      reader.quantity_or("slip_step", Quantity::force_N, kDefaultSlipStep_N, ranges::kPositiveForce_N);
  reader.finish();
  return limits;
}

PlantModel parse_plant(ObjectReader& reader) {
  PlantModel plant;
  plant.mass_kg = reader.quantity("mass", Quantity::mass_kg, kHandleMass_kg);
  plant.viscous_N_s_per_m =
      reader.quantity("viscous", Quantity::damping_N_s_per_m, ranges::kDamping_N_s_per_m);
  plant.coulomb_N = reader.quantity("coulomb", Quantity::force_N, ranges::kForce_N);
  std::tie(plant.end_stop_min_m, plant.end_stop_max_m) =
      reader.range("end_stops", Quantity::length_m, ranges::kPosition_m);
  plant.end_stop_stiffness_N_per_m =
      reader.quantity("end_stop_stiffness", Quantity::stiffness_N_per_m, ranges::kPositiveStiffness_N_per_m);
  plant.sensor_noise_counts =
      reader.quantity("sensor_noise_counts", Quantity::dimensionless, ranges::kNoise_counts);
  reader.finish();
  return plant;
}

bool looks_like_path(const std::string& name_or_path) {
  return name_or_path.find('/') != std::string::npos ||
         (name_or_path.size() > 5 && name_or_path.ends_with(".json"));
}

constexpr int kMaxProfileExtends = 8;

}  // namespace

DeviceProfile parse_device_profile(std::string_view json_text, const std::string& display_name) {
  const nlohmann::json root = parse_json_text(json_text, display_name);
  ObjectReader reader(root, "", display_name);
  DeviceProfile profile;
  // A 2-DOF profile is refused before any other key, naming what it is.
  if (reader.choice("kind", {"capstan", "planar"}, "capstan") == "planar") {
    reader.fail("kind", "a 2-DOF (planar) profile: a 1-DOF device needs a 1-DOF profile such as \"hapkit3\"");
  }
  profile.name = reader.string("name");
  profile.source = display_name;
  reader.string_or("description", "");  // for people: checked to be text, not kept
  profile.sensor = reader.part("sensor", parse_sensor);
  profile.drive = reader.part("drive", parse_drive);
  profile.limits = reader.part("limits", parse_limits);
  profile.plant = reader.part("plant", parse_plant);
  reader.finish();
  return profile;
}

std::string profile_kind_of(std::string_view json_text) noexcept {
  try {
    const nlohmann::json root = nlohmann::json::parse(json_text, nullptr, false);
    if (!root.is_object()) return "";
    const auto kind = root.find("kind");
    if (kind == root.end()) return "capstan";
    return kind->is_string() ? kind->get<std::string>() : "";
  } catch (...) {
    return "";  // allocation failure: no kind
  }
}

bool names_planar_profile(const std::string& name_or_path, const std::string& base_dir) noexcept {
  try {
    // Resolved: a profile that extends a planar one is planar.
    return profile_kind_of(find_profile_text(name_or_path, base_dir, false).json_text) == "planar";
  } catch (...) {
    // Unreadable: the loader that reads it reports why.
  }
  return false;
}

namespace {

// A profile's own text, by name (shipped) or by path.
ProfileText find_profile_file(const std::string& name_or_path, const std::string& base_dir, bool planar) {
  if (looks_like_path(name_or_path)) {
    std::filesystem::path path(name_or_path);
    if (path.is_relative() && !base_dir.empty()) path = std::filesystem::path(base_dir) / path;
    const std::string shown = path.lexically_normal().string();
    return ProfileText{read_text_file(shown, kMaxJsonFileBytes), shown};
  }
  std::vector<std::string_view> names;
  for (const BuiltinProfile& builtin : builtin_profiles()) {
    if (builtin.name == name_or_path) {
      return ProfileText{std::string(builtin.json_text), "environments/devices/" + std::string(builtin.name) + ".json"};
    }
    if ((profile_kind_of(builtin.json_text) == "planar") == planar) names.push_back(builtin.name);
  }
  std::string message = std::string(planar ? "unknown planar device profile" : "unknown device profile") + " \"" +
                        name_or_path + "\"";
  const std::string suggestion = nearest_name(name_or_path, names);
  if (!suggestion.empty()) message += " (did you mean \"" + suggestion + "\"?)";
  throw UnknownProfileError(message);
}

// A profile that "extends" another: the parent's JSON (itself resolved, at most
// kMaxProfileExtends deep) with the child's keys merged over it (objects key by key,
// anything else replaced; RFC 7386, so a null removes a parent's key). Without "extends"
// the text is returned as it is, so errors keep their line and column.
ProfileText resolve_extends(ProfileText profile, const std::string& base_dir, bool planar, int depth) {
  const nlohmann::json child = parse_json_text(profile.json_text, profile.display_name);
  if (!child.is_object() || !child.contains("extends")) return profile;
  const nlohmann::json& extends = child["extends"];
  if (!extends.is_string() || extends.get<std::string>().empty()) {
    throw InputError(profile.display_name + ": /extends: expected the name or path of the profile to extend, got " +
                     json_type_name(extends));
  }
  if (depth >= kMaxProfileExtends) {
    throw InputError(profile.display_name + ": /extends: more than " + std::to_string(kMaxProfileExtends) +
                     " profiles extend each other (a loop?)");
  }
  const std::string parent_name = extends.get<std::string>();
  ProfileText parent;
  try {
    parent = find_profile_file(parent_name, base_dir, planar);
  } catch (const InputError& error) {
    throw InputError(profile.display_name + ": /extends: " + error.what());
  }
  const std::string parent_dir = std::filesystem::path(parent.display_name).parent_path().string();
  parent = resolve_extends(std::move(parent), looks_like_path(parent_name) ? parent_dir : base_dir, planar, depth + 1);
  nlohmann::json merged = nlohmann::json::parse(parent.json_text);
  nlohmann::json patch = child;
  patch.erase("extends");
  merged.merge_patch(patch);
  return ProfileText{merged.dump(), profile.display_name + " (extends " + parent_name + ")"};
}

}  // namespace

ProfileText find_profile_text(const std::string& name_or_path, const std::string& base_dir, bool planar) {
  ProfileText profile = find_profile_file(name_or_path, base_dir, planar);
  const std::string dir = looks_like_path(name_or_path)
                              ? std::filesystem::path(profile.display_name).parent_path().string()
                              : base_dir;
  return resolve_extends(std::move(profile), dir, planar, 0);
}

std::string profile_source(const std::string& name_or_path, const std::string& display_name) {
  return looks_like_path(name_or_path) ? display_name : name_or_path + " (built-in profile)";
}

DeviceProfile load_device_profile(const std::string& name_or_path, const std::string& base_dir) {
  const ProfileText text = find_profile_text(name_or_path, base_dir, /*planar=*/false);
  DeviceProfile profile = parse_device_profile(text.json_text, text.display_name);
  profile.source = profile_source(name_or_path, text.display_name);
  return profile;
}

}  // namespace hapscene
