#pragma once
// A 2-DOF (planar) device profile: the Haplink, a pantograph of two Hapkits, the Haply
// 2DIY. Loaded from JSON (environments/devices/*.json with "kind": "planar"); the 1-DOF
// loader (engine/devices/profile.hpp) refuses these files and this loader refuses 1-DOF
// ones, each naming the other. Every number is SI once parsed (angles in rad, torques in
// N m); docs/reference/devices-2d.md describes each shipped profile's task frame.
//
// The parts, per tick (engine/devices/planar/planar_model.hpp):
//   raw reading per joint --sensor--> sensed angle --coupling--> joint angles q
//   q --linkage--> handle position p and Jacobian J (engine/devices/planar/linkage.hpp)
//   force F --J^T--> joint torques --coupling^T, transmission, direction--> motor torques
//   --drive--> what each motor driver takes (duty and direction pin, or a torque in N m)
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/base/errors.hpp"
#include "engine/devices/planar/linkage.hpp"
#include "engine/devices/profile.hpp"

namespace hapscene {

// What a joint's sensor reports ("sensor": {"type": ...}).
enum class PlanarSensorKind : std::uint8_t {
  mr,       // the Hapkit's MR sensor: wrapping ADC counts, calibrated to the joint's angle
  encoder,  // an incremental encoder on the motor shaft: counts per motor revolution
  angle,    // the board reports the joint angle itself, in degrees (the Haply board)
};

// One joint's sensor. The joint's sensed angle (rad), before the coupling:
//   mr:      slope_deg_per_count * unwrapped counts + offset       (deg to rad)
//   encoder: direction_sign * counts * 2 pi / counts_per_revolution * transmission ratio + offset
//   angle:   the reported degrees (to rad) + offset
struct PlanarSensor {
  PlanarSensorKind kind{PlanarSensorKind::encoder};
  double offset_rad{};                  // the joint's angle at count 0 (mr, encoder; angle: added)
  // mr
  double counts_to_deg_slope{};
  std::int32_t min_counts{};
  std::int32_t span_counts{};
  std::int32_t flip_threshold_counts{};
  // encoder; angle (the board's own encoder, sent to it at setup: "counts_per_revolution")
  double counts_per_revolution{};
  int direction_sign{1};                // encoder: +1 counts up with the motor's positive turn
  // angle: what a Haply-style board is told at setup (the board presets its counter so the
  // reported angle is board_offset at the reference pose, counting in board_direction).
  double board_offset_rad{};
  bool board_counter_clockwise{};
};

// How a motor torque becomes the driver's command ("drive": {"law": ...}).
enum class PlanarDriveLaw : std::uint8_t {
  sqrt,    // duty = sqrt(|torque| / Km) (the Hapkit 3.0)
  linear,  // duty = |torque| * duty_per_N_m (the Haplink: 65.13 per N m)
  torque,  // the board takes a torque in N m and clamps it (the Haply board: 0.123 N m)
};

struct PlanarDrive {
  PlanarDriveLaw law{PlanarDriveLaw::linear};
  double motor_constant_N_m{};   // sqrt: Km, the torque at full duty
  double duty_per_N_m{};         // linear
  double duty_max{1.0};          // sqrt, linear: the highest duty the host commands
  double torque_max_N_m{};       // torque: the clamp
  int direction_sign{1};         // +1: a positive motor torque drives the direction pin high
  int pwm_levels{};              // sqrt, linear: PWM steps at full duty (0: not given)
  bool board_counter_clockwise{};  // torque: the motor direction a Haply-style board is told at setup
};

// One joint: its sensor, its capstan (motor pulley and sector radii; a direct drive has
// ratio 1) and its motor's drive.
struct PlanarJoint {
  PlanarSensor sensor;
  double transmission_ratio{1.0};  // pulley_radius / sector_radius: joint turns per motor turn
  PlanarDrive drive;
  // A Haply-style board (an angle sensor and a torque drive): the board port (1..4) of the
  // joint's encoder and motor. Default: the joint's number.
  int board_port{};
};

// Task-space region where force may be rendered: a box, or a simple polygon.
struct PlanarWorkspace {
  bool is_box{true};
  Vec2 box_min_m{};
  Vec2 box_max_m{};
  std::vector<Vec2> polygon_m;     // counter-clockwise or clockwise, not closed (no repeat)
};

// True when p is inside the workspace (boundary included). Not for the tick (a polygon is
// a scan); the tick's safety stage owns its own compiled test.
bool workspace_contains(const PlanarWorkspace& workspace, const Vec2& p_m) noexcept;

// The workspace's bounding box: the box itself, or the polygon's.
void workspace_bounds(const PlanarWorkspace& workspace, Vec2* low_m, Vec2* high_m) noexcept;

// Empty when the box [low, high] lies within the workspace; else why not, to follow
// "must lie within the device's workspace: ": a corner of the box outside it, or (a
// polygon, which need not be convex) the edge of the polygon that passes through the
// box's inside ("edge 2 (points 2 to 3) of the device's polygon passes through the box").
std::string box_leaves_workspace(const PlanarWorkspace& workspace, const Vec2& low_m, const Vec2& high_m);

struct PlanarLimits {
  double max_force_N{};
  double slew_limit_N_per_s{};
  double soft_start_s{};
  double soft_start_threshold_N{};
  // Above this condition number of J (cond >= 1) the pose counts as near a singularity:
  // force ramps to zero and the event is counted.
  double condition_limit{};
  PlanarWorkspace workspace;
};

// A link's mass estimate for the simulated plant: mass, inertia about its centre of mass,
// and where the centre sits, as a distance from the link's proximal joint along the link.
struct PlanarLinkMass {
  double mass_kg{};
  double inertia_kg_m2{};
  double center_of_mass_m{};
};

// Physical estimates for a simulated 2-DOF device (not used with real hardware).
// links: serial_2r: [link a, link b]; five_bar: [proximal 1, proximal 2, distal 1, distal 2].
struct PlanarPlantEstimates {
  std::array<PlanarLinkMass, 4> links{};
  int link_count{};
  double handle_mass_kg{};
  Vec2 rotor_inertia_kg_m2{};          // each motor's rotor, reflected to its joint
  Vec2 viscous_N_m_s_per_rad{};        // per joint
  Vec2 coulomb_N_m{};                  // per joint
  std::array<Vec2, 2> end_stops_rad{}; // per joint: {min, max} of q (before the coupling)
  double end_stop_stiffness_N_m_per_rad{};
  double sensor_noise_counts{};        // standard deviation (0: none)
};

// The task frame as the profile documents it (text for people; not used in computation).
struct PlanarFrame {
  std::string origin;
  std::string x_axis;
  std::string y_axis;
};

struct PlanarProfile {
  std::string name;
  std::string source;  // its file, or "NAME (built-in profile)" (DeviceProfile::source)
  PlanarFrame frame;
  Linkage linkage;
  std::array<PlanarJoint, 2> joints{};
  // Joint 2's angle gains coupling x joint 1's angle (the Haplink's second motor drives
  // link b through joint 1's motion): q2 = sensed_2 + coupling * q1. 0: independent joints.
  double coupling{};
  Vec2 home_m{};                   // the handle at rest / reference pose, task frame
  PlanarLimits limits;
  PlanarPlantEstimates plant;
  // Two Hapkit boards (`--device serial:A,B`): the USB serial number of joint 1's board and
  // of joint 2's, as `hapscene devices` lists them, so swapped cables are caught. Empty:
  // not checked (a kit's own profile sets them, usually one that extends the shipped one).
  std::array<std::string, 2> board_serials{};
};

// Loads a planar profile by name ("haplink": shipped and compiled in) or by path (contains
// a "/" or ends in ".json"; relative paths from `base_dir`). Throws InputError (an unknown
// name: UnknownProfileError, with the nearest planar name).
PlanarProfile load_planar_profile(const std::string& name_or_path, const std::string& base_dir);

// Parses a planar profile from JSON text; `display_name` names it in messages.
PlanarProfile parse_planar_profile(std::string_view json_text, const std::string& display_name);

// The value of "kind" a profile file gives: "planar" for 2-DOF profiles; 1-DOF profiles
// may say "capstan" or leave it out.
inline constexpr std::string_view kPlanarProfileKind = "planar";
inline constexpr std::string_view kCapstanProfileKind = "capstan";

}  // namespace hapscene
