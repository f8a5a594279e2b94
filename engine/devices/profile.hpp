#pragma once
// A device profile: everything hapscene knows about one kind of device, loaded from JSON
// (environments/devices/*.json). The host uses the sensor and drive parts to turn counts
// into a handle position and a force into a PWM duty; the simulator also uses the plant.
#include <cstdint>
#include <string>
#include <string_view>

#include "engine/base/errors.hpp"

namespace hapscene {

// What the sensor reports ("sensor": {"type": ...}).
enum class SensorKind : std::uint8_t {
  mr,       // magnetoresistive angle sensor on an ADC: wraps every period, unwrapped by flips
  encoder,  // an incremental encoder's counter: continuous, never wraps
};

// How a motor torque becomes a PWM duty ("drive": {"duty_law": ...}).
enum class DutyLaw : std::uint8_t {
  sqrt,    // torque = Km * duty^2: the Hapkit 3.0 reference code's law
  linear,  // torque = Km * duty: a driver whose torque follows the duty (the Haplink's)
};

// The sensor: raw counts to sector angle. An MR sensor (the Hapkit's) is read by a 10-bit
// ADC and repeats every half turn of the motor shaft: unwrapped counts = raw + flips *
// span_counts. An encoder's counts are already continuous (min, span and flip threshold
// are not used).
struct SensorModel {
  SensorKind kind{SensorKind::mr};
  double counts_to_deg_slope{};     // sector angle per unwrapped count (deg/count)
  double counts_to_deg_offset{};    // sector angle at count 0 (deg)
  std::int32_t min_counts{};        // lowest raw reading of one period
  std::int32_t span_counts{};       // raw counts in one sensor period
  std::int32_t flip_threshold_counts{};  // a jump larger than this between samples is a flip
};

// Capstan drive: motor pulley, sector pulley and handle.
struct DriveModel {
  double handle_radius_m{};
  double pulley_radius_m{};
  double sector_radius_m{};
  DutyLaw duty_law{DutyLaw::sqrt};
  double motor_constant_N_m{};  // motor torque at full duty (Km)
  double duty_max{};            // highest duty the host commands, in [0, 1]
  int direction_sign{1};        // +1: positive force drives the direction pin high
  int pwm_levels{};             // PWM steps at full duty (255 for Arduino analogWrite)
};

// Safety limits of the device itself; an environment may only lower them.
struct DeviceLimits {
  double max_force_N{};
  double slew_limit_N_per_s{};
  double workspace_min_m{};
  double workspace_max_m{};
  double soft_start_s{};             // ramp-in duration when a run starts in a force field
  double soft_start_threshold_N{};   // first-tick force above which the ramp is used
  // Capstan slip risk (checked by the harness, not clamped): a commanded force above
  // slip_force_N, or a change of more than slip_step_N within 1 ms, may make the cable
  // slip on the motor pulley. Optional in profiles; defaults below.
  double slip_force_N{};
  double slip_step_N{};
};

// Defaults when a profile gives no slip limits: the Hapkit 3.0's estimates (a firm
// push is about 5 N; a jolt of 2 N within a millisecond is felt as a click of the cable).
inline constexpr double kDefaultSlipForce_N = 5.0;
inline constexpr double kDefaultSlipStep_N = 2.0;

// Physical parameters for the simulated device (not used with real hardware).
struct PlantModel {
  double mass_kg{};                  // effective mass at the handle
  double viscous_N_s_per_m{};        // physical damping b
  double coulomb_N{};                // dry friction
  double end_stop_min_m{};           // hard stops of the handle's travel
  double end_stop_max_m{};
  double end_stop_stiffness_N_per_m{};
  double sensor_noise_counts{};      // standard deviation of sensor noise (0: none)
};

struct DeviceProfile {
  std::string name;
  // Where it came from, for every message about it after parsing (with profile_place()):
  // its file ("my_kit.json", "my_kit.json (extends hapkit3)"), or "hapkit3 (built-in
  // profile)" for a compiled-in one.
  std::string source;
  SensorModel sensor;
  DriveModel drive;
  DeviceLimits limits;
  PlantModel plant;
};

// A profile name that is neither shipped nor a path; the caller knows where it was written.
class UnknownProfileError : public InputError {
 public:
  using InputError::InputError;
};

// "SOURCE: POINTER" ("my_kit.json: /sensor"): names the profile and the key that a check
// made after parsing (at device open, at kinematics setup, by calibrate) objects to.
inline std::string profile_place(const std::string& source, std::string_view pointer) {
  return source + ": " + std::string(pointer);
}

// The source a profile loaded by `name_or_path` is given: the file it was read from
// (`display_name`), or "NAME (built-in profile)" for a compiled-in one.
std::string profile_source(const std::string& name_or_path, const std::string& display_name);

// Loads a profile by name ("hapkit3": shipped and compiled in) or by path (contains a
// "/" or ends in ".json"; relative paths are taken from `base_dir`). Throws InputError.
DeviceProfile load_device_profile(const std::string& name_or_path, const std::string& base_dir);

// A profile's text and the name messages give it ("environments/devices/hapkit3.json" for
// a shipped one), found by name (shipped) or by path (relative to `base_dir`). A name
// that is not shipped is an UnknownProfileError suggesting the nearest shipped name of
// the same kind (planar or not).
struct ProfileText {
  std::string json_text;
  std::string display_name;
};
ProfileText find_profile_text(const std::string& name_or_path, const std::string& base_dir, bool planar);

// True when `name_or_path` (as load_device_profile takes it) is a readable planar (2-DOF)
// profile ("kind": "planar"); false otherwise, errors included (the loader reports them).
bool names_planar_profile(const std::string& name_or_path, const std::string& base_dir) noexcept;

// Parses a profile from JSON text; `display_name` names it in messages. Throws InputError.
// A 2-DOF profile ("kind": "planar", engine/devices/planar/planar_profile.hpp) is refused
// with a message that says so.
DeviceProfile parse_device_profile(std::string_view json_text, const std::string& display_name);

// The "kind" a profile's JSON text declares: "planar" (2-DOF), "capstan" (1-DOF, also when
// absent), or "" when the text is not a JSON object. For choosing a loader and for
// suggesting names of the right kind; throws nothing.
std::string profile_kind_of(std::string_view json_text) noexcept;

}  // namespace hapscene
