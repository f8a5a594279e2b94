#pragma once
// The simulated physics and sensors of a 2-DOF device of either kinematics family
// (linkage.hpp), driven by two motor torques held over each tick (the board's sample and
// hold) and by the 2-D virtual hand's force on the handle:
//
//   M(q) q_ddot + c(q, q_dot) = T tau_motor + J(q)^T F_hand + tau_stops - B q_dot - tau_coulomb
//
// - q: the linkage's joint angles (rad). Motor angles are T^T q, where T (motor_to_joint)
//   maps motor torques to joint torques (a capstan ratio, the Haplink's coupling of its
//   second joint to the first, or the identity for direct drive).
// - M(q): every link a rigid body (mass, centre of mass on the line between its ends,
//   inertia about the centre of mass), the handle a point mass (plus the hand's mass while
//   it grips), the motors' rotors reflected through T. The links' ends come from
//   solve_linkage: serial_2r: link a from the base to the elbow, link b from the elbow to
//   the handle; five_bar: the proximal links from each base to its elbow and the distal
//   links from each elbow to the handle.
// - c(q, q_dot): the Coriolis and centrifugal terms, analytic (Kane's form): each body's
//   centre-of-mass acceleration and angular acceleration at q_ddot = 0, from the ends'
//   accelerations (a proximal end turning about its base: -w^2 r; the five-bar's handle:
//   the second derivative of its two closure constraints |p - e_i| = L_i; a serial arm's
//   handle: the elbow's plus -w_b^2 (p - e)). This equals the Christoffel form built from
//   dM/dq (tests/devices/planar_plant_dynamics_test.cpp checks it against finite
//   differences of M), and keeps d/dt (q_dot^T M q_dot / 2) = q_dot^T tau exactly.
// - Joint friction: viscous B and Coulomb (stick-slip per joint: a joint at rest stays at
//   rest while the torque holding it is below its Coulomb level; a joint whose velocity
//   would change sign within a substep stops at the crossing, located linearly, as the
//   1-D plant does); end stops: stiff springs with damping beyond each joint's range that
//   only push; motor torque limits clamp each motor's command.
// - Integration: classical RK4 (default: 4 substeps per 1 kHz tick, which keeps the stiff
//   end stops' energy to 1e-4; engine/bench/planar_accuracy.hpp measures the error) or
//   semi-implicit Euler, with the friction directions and the stuck joints fixed over a
//   substep, and each substep split where a joint passes an end stop's edge (located on
//   the cubic through the step's ends), where the stop force has a kink.
// - Sensor: per motor, the motor angle in counts (angle per count, zero angle), nearest
//   count plus optional seeded noise, optionally wrapping every period (an MR sensor) or a
//   32-bit counter (an encoder).
// Deterministic for a given seed. No allocation or exception after construction.
#include <array>
#include <cstdint>
#include <limits>
#include <string_view>

#include "engine/base/axes.hpp"
#include "engine/devices/noise.hpp"
#include "engine/devices/planar/linkage.hpp"
#include "engine/devices/planar/planar_hand.hpp"

namespace hapscene {

enum class PlanarIntegrator : std::uint8_t { semi_implicit_euler, rk4 };

inline constexpr std::string_view kPlanarIntegratorNames[] = {"euler", "rk4"};

// A 2x2 matrix, rows first.
struct Matrix2 {
  double m[2][2]{{1.0, 0.0}, {0.0, 1.0}};
};

// One link as a rigid body between its two ends (see the order in PlanarPlantParameters).
struct LinkBody {
  double mass_kg{};
  double com_fraction{0.5};   // centre of mass on the line between the ends: 0 first, 1 second
  double inertia_kg_m2{};     // about the centre of mass
};

inline constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// Estimates in a profile: the kits' masses and friction are not published.
struct PlanarPlantParameters {
  Linkage linkage;
  // serial_2r: [0] link a (base to elbow), [1] link b (elbow to handle), [2], [3] unused.
  // five_bar: [0], [1] proximal links (base i to elbow i), [2], [3] distal links (elbow i
  // to the handle).
  LinkBody links[4]{};
  double handle_mass_kg{};
  Matrix2 motor_to_joint{};                  // T: joint torques = T motor torques
  Vec2 rotor_inertia_kg_m2{};                // per motor, about its own axis
  Vec2 motor_torque_limit_N_m{{kNoLimit, kNoLimit}};
  Vec2 viscous_N_m_s_per_rad{};              // per joint
  Vec2 coulomb_N_m{};                        // per joint (0: none)
  Vec2 stop_min_rad{{-kNoLimit, -kNoLimit}}; // per joint
  Vec2 stop_max_rad{{kNoLimit, kNoLimit}};
  Vec2 stop_stiffness_N_m_per_rad{};
  Vec2 stop_damping_N_m_s_per_rad{};
  // Sensor, per motor: counts = nearest((motor angle - zero) / step), wrapped into
  // [min, min + period) when period > 0. A negative step counts the other way.
  Vec2 sensor_step_rad{{1e-3, 1e-3}};
  Vec2 sensor_zero_rad{};
  std::array<std::int32_t, 2> sensor_min_counts{};
  std::array<std::int32_t, 2> sensor_period_counts{};
  double sensor_noise_counts{};              // standard deviation (0: none)
};

struct PlanarSimulationConfig {
  Vec2 start_q_rad{};
  Vec2 start_q_dot_rad_per_s{};
  PlanarHandConfig hand;  // none by default
  std::uint64_t noise_seed{1};
  PlanarIntegrator integrator{PlanarIntegrator::rk4};
  int substeps_per_tick{4};
};

// The equations of motion at one state: M(q) q_ddot + bias = generalized forces.
struct PlanarDynamics {
  LinkagePose pose;
  Matrix2 mass{};                 // M(q), kg m^2
  Vec2 bias_N_m{};                // c(q, q_dot)
  Vec2 handle_velocity_m_per_s{};
  Vec2 handle_bias_m_per_s2{};    // the handle's acceleration at q_ddot = 0
};

// The mass model, prepared from the parameters (the elbows' turning rates are measured
// once from solve_linkage, so any angle convention of a family works).
class PlanarMassModel {
 public:
  // `reference_q_rad` must be a pose where the linkage closes. Throws InputError when it
  // does not, or when a parameter is negative or non-finite.
  PlanarMassModel(const PlanarPlantParameters& parameters, const Vec2& reference_q_rad);

  // M and c at (q, q_dot) with `extra_handle_mass_kg` on the handle (a gripping hand).
  // False where the linkage does not close. No allocation, no throw.
  bool evaluate(const Vec2& q_rad, const Vec2& q_dot_rad_per_s, double extra_handle_mass_kg,
                PlanarDynamics* out) const noexcept;

 private:
  PlanarPlantParameters parameters_;
  Matrix2 rotor_mass_{};        // T diag(rotor) T^T
  double elbow_rate_[2]{1.0, 1.0};  // d(proximal link angle) / d q_i
};

class PlanarPlant {
 public:
  // Throws InputError for parameters or a configuration that cannot be simulated (a start
  // pose where the linkage does not close, a singular mass matrix, a zero sensor step,
  // substeps < 1, a bad hand path).
  PlanarPlant(const PlanarPlantParameters& parameters, const PlanarSimulationConfig& config);

  // The motor command, held until the next one: clamped to each motor's limit (a clamp
  // counts as a saturation; a non-finite torque is taken as 0 and counted as a fault).
  void hold_motor_torques(const Vec2& motor_torque_N_m) noexcept;
  // One tick: substeps_per_tick substeps of dt / substeps with the held command.
  void advance(double dt_s) noexcept;
  // One integration step by the configured integrator.
  void substep(double h_s) noexcept;

  // Each motor's sensor reading now (see PlanarPlantParameters). A reading that cannot be
  // formed (non-finite or beyond the counter) is answered with the last good one, counted.
  std::array<std::int32_t, 2> sensor_counts() noexcept;

  Vec2 q_rad() const noexcept { return q_rad_; }
  Vec2 q_dot_rad_per_s() const noexcept { return q_dot_rad_per_s_; }
  Vec2 handle_m() const noexcept { return pose_.handle_m; }
  Vec2 handle_velocity_m_per_s() const noexcept {
    return hapscene::handle_velocity_m_per_s(pose_.jacobian, q_dot_rad_per_s_);
  }
  const LinkagePose& pose() const noexcept { return pose_; }
  double t_s() const noexcept { return t_s_; }
  Vec2 motor_torque_N_m() const noexcept { return motor_torque_N_m_; }  // held, after clamping
  Vec2 joint_torque_N_m() const noexcept { return joint_torque_N_m_; }  // T times the above
  Vec2 hand_force_N() const noexcept { return hand_force_N_; }          // at the last substep's start
  // The device's kinetic energy q_dot^T M q_dot / 2 (not the hand's mass), and the energy
  // stored in the end stops' springs.
  double kinetic_energy_J() const noexcept;
  double stop_energy_J() const noexcept;

  std::uint64_t saturations() const noexcept { return saturations_; }
  // Substeps that left the linkage's closable range or went non-finite: the joints stop
  // where they were (the pose kept, velocity zero).
  std::uint64_t linkage_faults() const noexcept { return linkage_faults_; }
  std::uint64_t command_faults() const noexcept { return command_faults_; }
  std::uint64_t sensor_faults() const noexcept { return sensor_faults_; }

  const PlanarPlantParameters& parameters() const noexcept { return parameters_; }
  const PlanarSimulationConfig& config() const noexcept { return config_; }
  // The live view's pointer takes the hand while active (hand_pointer.hpp).
  void follow(const HandPointerOf<2>* pointer) noexcept { hand_.follow(pointer); }
  const PlanarHand& hand() const noexcept { return hand_; }
  const PlanarMassModel& mass_model() const noexcept { return model_; }

 private:
  // Per joint over one substep: +1/-1 the direction Coulomb friction opposes, or 0 with
  // `stuck` (held by static friction) or without (no Coulomb friction on that joint).
  struct Friction {
    double direction[2]{};
    bool stuck[2]{};
  };
  // Accelerations at a state with the friction fixed; `holding_N_m` the torque each stuck
  // joint's friction must resist. False where the linkage does not close.
  bool acceleration(double t_s, const Vec2& q, const Vec2& q_dot, const Friction& friction, Vec2* q_ddot,
                    Vec2* holding_N_m) const noexcept;
  bool integrate(double t_s, double h_s, const Friction& friction) noexcept;
  void settle_stuck_joints(double t_s, Friction* friction) const noexcept;
  Vec2 stop_torque_N_m(const Vec2& q, const Vec2& q_dot) const noexcept;

  PlanarPlantParameters parameters_;
  PlanarSimulationConfig config_;
  PlanarMassModel model_;
  PlanarHand hand_;
  GaussianNoise noise_;
  Vec2 q_rad_{};
  Vec2 q_dot_rad_per_s_{};
  LinkagePose pose_{};
  double t_s_{};
  double t_carry_s_{};
  Vec2 motor_torque_N_m_{};
  Vec2 joint_torque_N_m_{};
  Vec2 hand_force_N_{};
  std::array<std::int32_t, 2> last_counts_{};
  std::uint64_t saturations_{};
  std::uint64_t linkage_faults_{};
  std::uint64_t command_faults_{};
  std::uint64_t sensor_faults_{};
};

// Motor torques that give the joint torques `joint_torque_N_m` (T^-1 tau): an ideal drive,
// for benches and tests. Zero when T is singular.
Vec2 motor_torques_for_joint_torques(const PlanarPlantParameters& parameters, const Vec2& joint_torque_N_m) noexcept;

// Joint angles that put the handle at `handle_m` (Newton's method from `guess_q_rad`, so
// the branch is the guess's). False when it does not converge to 1 nm.
bool joint_angles_for_handle(const Linkage& linkage, const Vec2& handle_m, const Vec2& guess_q_rad,
                             Vec2* q_rad) noexcept;

}  // namespace hapscene
