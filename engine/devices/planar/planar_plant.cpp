#include "engine/devices/planar/planar_plant.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

Vec2 perp(const Vec2& v) noexcept { return Vec2{{-v[1], v[0]}}; }

// A point of the mechanism: its position, its velocity per joint rate (the Jacobian's
// columns) and its acceleration at q_ddot = 0.
struct Point {
  Vec2 p_m{};
  Vec2 column[2]{};
  Vec2 bias_m_per_s2{};
};

// Adds one rigid link between points a and b to M and c (Kane's equations): its centre of
// mass moves with (1 - s) a + s b, and it turns at w = cross(d, d_dot) / |d|^2, d = b - a,
// whose derivative at q_ddot = 0 is cross(d, d_ddot) / |d|^2 (cross(d_dot, d_dot) = 0).
void add_link(const LinkBody& body, const Point& a, const Point& b, Matrix2* mass, Vec2* bias) noexcept {
  if (body.mass_kg == 0.0 && body.inertia_kg_m2 == 0.0) return;
  const double s = body.com_fraction;
  const Vec2 d = b.p_m - a.p_m;
  const double length2 = dot(d, d);
  Vec2 com_column[2];
  double turn[2];
  for (int j = 0; j < 2; ++j) {
    com_column[j] = (1.0 - s) * a.column[j] + s * b.column[j];
    turn[j] = cross(d, b.column[j] - a.column[j]) / length2;
  }
  const Vec2 com_bias = (1.0 - s) * a.bias_m_per_s2 + s * b.bias_m_per_s2;
  const double turn_bias = cross(d, b.bias_m_per_s2 - a.bias_m_per_s2) / length2;
  for (int j = 0; j < 2; ++j) {
    for (int k = 0; k < 2; ++k) {
      mass->m[j][k] += body.mass_kg * dot(com_column[j], com_column[k]) + body.inertia_kg_m2 * turn[j] * turn[k];
    }
    (*bias)[j] += body.mass_kg * dot(com_column[j], com_bias) + body.inertia_kg_m2 * turn[j] * turn_bias;
  }
}

void add_point_mass(double mass_kg, const Point& a, Matrix2* mass, Vec2* bias) noexcept {
  if (mass_kg == 0.0) return;
  for (int j = 0; j < 2; ++j) {
    for (int k = 0; k < 2; ++k) mass->m[j][k] += mass_kg * dot(a.column[j], a.column[k]);
    (*bias)[j] += mass_kg * dot(a.column[j], a.bias_m_per_s2);
  }
}

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("planar plant: " + what);
}

bool non_negative(double v) { return std::isfinite(v) && v >= 0.0; }
bool non_negative(const Vec2& v) { return non_negative(v[0]) && non_negative(v[1]); }

void check_parameters(const PlanarPlantParameters& p) {
  for (int i = 0; i < 4; ++i) {
    const std::string name = "link " + std::to_string(i + 1);
    require(non_negative(p.links[i].mass_kg), name + " mass must be finite and >= 0");
    require(non_negative(p.links[i].inertia_kg_m2), name + " inertia must be finite and >= 0");
    require(std::isfinite(p.links[i].com_fraction), name + " centre of mass must be finite");
  }
  require(non_negative(p.handle_mass_kg), "handle mass must be finite and >= 0");
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) require(std::isfinite(p.motor_to_joint.m[i][j]), "the motor-to-joint matrix must be finite");
    const std::string joint = "joint " + std::to_string(i + 1);
    require(!std::isnan(p.motor_torque_limit_N_m[i]) && p.motor_torque_limit_N_m[i] >= 0.0,
            "motor " + std::to_string(i + 1) + " torque limit must be >= 0");
    require(!std::isnan(p.stop_min_rad[i]) && !std::isnan(p.stop_max_rad[i]) && p.stop_min_rad[i] <= p.stop_max_rad[i],
            joint + " end stops must have min <= max");
    require(std::isfinite(p.sensor_step_rad[i]) && p.sensor_step_rad[i] != 0.0,
            "sensor " + std::to_string(i + 1) + " step must be finite and non-zero");
    require(std::isfinite(p.sensor_zero_rad[i]), "sensor " + std::to_string(i + 1) + " zero must be finite");
    require(p.sensor_period_counts[i] >= 0, "sensor " + std::to_string(i + 1) + " period must be >= 0");
  }
  require(non_negative(p.rotor_inertia_kg_m2), "rotor inertias must be finite and >= 0");
  require(non_negative(p.viscous_N_m_s_per_rad), "viscous friction must be finite and >= 0");
  require(non_negative(p.coulomb_N_m), "Coulomb friction must be finite and >= 0");
  require(non_negative(p.stop_stiffness_N_m_per_rad), "end stop stiffness must be finite and >= 0");
  require(non_negative(p.stop_damping_N_m_s_per_rad), "end stop damping must be finite and >= 0");
  require(non_negative(p.sensor_noise_counts), "sensor noise must be finite and >= 0");
}

double sign_of(double v) noexcept { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

// Where, as a fraction of a step, a joint passed `level`: the root of the cubic Hermite
// interpolant through its angles and rates at both ends (the sign changes over [0, 1]), by
// bisection. Locates an end stop's edge to the integrator's order rather than to the step.
double crossing_fraction(double q0, double v0_dt, double q1, double v1_dt, double level) noexcept {
  const auto at = [&](double s) noexcept {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * q0 + (s3 - 2 * s2 + s) * v0_dt + (-2 * s3 + 3 * s2) * q1 + (s3 - s2) * v1_dt - level;
  };
  double low = 0.0, high = 1.0;
  const bool rising = at(0.0) < 0.0;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (low + high);
    if ((at(mid) < 0.0) == rising) low = mid;
    else high = mid;
  }
  return high;
}

// A joint this close to an end stop's edge at a step's start has just been placed there by
// a located crossing: not a crossing again.
constexpr double kOnEdge_rad = 1e-10;

}  // namespace

// ---- The mass model ----

PlanarMassModel::PlanarMassModel(const PlanarPlantParameters& parameters, const Vec2& reference_q_rad)
    : parameters_(parameters) {
  check_parameters(parameters);
  require(all_finite(reference_q_rad), "the start pose must be finite");
  require(solve_linkage(parameters.linkage, reference_q_rad).valid,
          "the linkage does not close at the start pose");
  // Reflected rotors: motor angles are T^T q, so their energy is q_dot^T T R T^T q_dot / 2.
  const Matrix2& t = parameters.motor_to_joint;
  for (int j = 0; j < 2; ++j) {
    for (int k = 0; k < 2; ++k) {
      rotor_mass_.m[j][k] = t.m[j][0] * parameters.rotor_inertia_kg_m2[0] * t.m[k][0] +
                            t.m[j][1] * parameters.rotor_inertia_kg_m2[1] * t.m[k][1];
    }
  }
  // How fast each proximal link turns per unit of its joint angle (+1 or -1 in every
  // sensible convention), by a central difference of the elbow around its base.
  const bool five_bar = parameters.linkage.family == LinkageFamily::five_bar;
  for (int i = 0; i < (five_bar ? 2 : 1); ++i) {
    constexpr double kStep_rad = 1e-6;
    Vec2 up = reference_q_rad, down = reference_q_rad;
    up[i] += kStep_rad;
    down[i] -= kStep_rad;
    const LinkagePose a = solve_linkage(parameters.linkage, up);
    const LinkagePose b = solve_linkage(parameters.linkage, down);
    const LinkagePose c = solve_linkage(parameters.linkage, reference_q_rad);
    require(a.valid && b.valid, "the linkage does not close next to the start pose");
    const Vec2 base = five_bar ? (i == 0 ? parameters.linkage.five_bar.base_1_m : parameters.linkage.five_bar.base_2_m)
                               : parameters.linkage.serial.base_m;
    const Vec2 elbow = i == 0 ? c.elbow_1_m : c.elbow_2_m;
    const Vec2 moved = i == 0 ? a.elbow_1_m - b.elbow_1_m : a.elbow_2_m - b.elbow_2_m;
    const Vec2 arm = elbow - base;
    const double rate = cross(arm, moved / (2.0 * kStep_rad)) / dot(arm, arm);
    require(std::abs(std::abs(rate) - 1.0) < 1e-4,
            "the linkage's proximal link " + std::to_string(i + 1) + " does not turn with its joint angle");
    elbow_rate_[i] = rate > 0.0 ? 1.0 : -1.0;
  }
  PlanarDynamics d;
  require(evaluate(reference_q_rad, Vec2{}, 0.0, &d), "the linkage does not close at the start pose");
  const double det = d.mass.m[0][0] * d.mass.m[1][1] - d.mass.m[0][1] * d.mass.m[1][0];
  require(d.mass.m[0][0] > 0.0 && det > 0.0,
          "the mass matrix is singular at the start pose (give the links, handle or rotors mass)");
}

bool PlanarMassModel::evaluate(const Vec2& q, const Vec2& q_dot, double extra_handle_mass_kg,
                               PlanarDynamics* out) const noexcept {
  const Linkage& linkage = parameters_.linkage;
  out->pose = solve_linkage(linkage, q);
  if (!out->pose.valid) return false;
  const LinkagePose& pose = out->pose;
  const Jacobian2& jac = pose.jacobian;

  Point handle;
  handle.p_m = pose.handle_m;
  handle.column[0] = Vec2{{jac.m[0][0], jac.m[1][0]}};
  handle.column[1] = Vec2{{jac.m[0][1], jac.m[1][1]}};
  const Vec2 v = handle_velocity_m_per_s(jac, q_dot);

  // An elbow turning about its base at w = rate q_dot_i: column i is rate perp(r), its
  // acceleration at q_ddot = 0 is -w^2 r.
  const auto elbow_point = [&](int i, const Vec2& base, const Vec2& elbow) noexcept {
    Point e;
    e.p_m = elbow;
    const Vec2 r = elbow - base;
    e.column[i] = elbow_rate_[i] * perp(r);
    const double w = elbow_rate_[i] * q_dot[i];
    e.bias_m_per_s2 = -(w * w) * r;
    return e;
  };

  Matrix2 mass = rotor_mass_;
  Vec2 bias{};
  if (linkage.family == LinkageFamily::serial_2r) {
    Point base;
    base.p_m = linkage.serial.base_m;
    const Point elbow = elbow_point(0, base.p_m, pose.elbow_1_m);
    // Link b turns at w_b = cross(d, p_dot - e_dot) / |d|^2 (its absolute angle is linear
    // in q), so the handle's acceleration at q_ddot = 0 is the elbow's minus w_b^2 d.
    const Vec2 d = handle.p_m - elbow.p_m;
    const Vec2 elbow_v = elbow.column[0] * q_dot[0];
    const double w_b = cross(d, v - elbow_v) / dot(d, d);
    handle.bias_m_per_s2 = elbow.bias_m_per_s2 - (w_b * w_b) * d;
    add_link(parameters_.links[0], base, elbow, &mass, &bias);
    add_link(parameters_.links[1], elbow, handle, &mass, &bias);
  } else {
    const FiveBarGeometry& g = linkage.five_bar;
    Point base_1, base_2;
    base_1.p_m = g.base_1_m;
    base_2.p_m = g.base_2_m;
    const Point elbow_1 = elbow_point(0, g.base_1_m, pose.elbow_1_m);
    const Point elbow_2 = elbow_point(1, g.base_2_m, pose.elbow_2_m);
    // Twice differentiating |p - e_i|^2 = L_i^2: u_i . p_ddot = u_i . e_i_ddot - |p_dot - e_i_dot|^2
    // with u_i = p - e_i; two equations for the handle's acceleration at q_ddot = 0.
    const Vec2 u1 = handle.p_m - elbow_1.p_m;
    const Vec2 u2 = handle.p_m - elbow_2.p_m;
    const Vec2 rel1 = v - elbow_1.column[0] * q_dot[0];
    const Vec2 rel2 = v - elbow_2.column[1] * q_dot[1];
    const double r1 = dot(u1, elbow_1.bias_m_per_s2) - dot(rel1, rel1);
    const double r2 = dot(u2, elbow_2.bias_m_per_s2) - dot(rel2, rel2);
    const double det = cross(u1, u2);
    if (det == 0.0) return false;
    handle.bias_m_per_s2 = Vec2{{(u2[1] * r1 - u1[1] * r2) / det, (u1[0] * r2 - u2[0] * r1) / det}};
    add_link(parameters_.links[0], base_1, elbow_1, &mass, &bias);
    add_link(parameters_.links[1], base_2, elbow_2, &mass, &bias);
    add_link(parameters_.links[2], elbow_1, handle, &mass, &bias);
    add_link(parameters_.links[3], elbow_2, handle, &mass, &bias);
  }
  add_point_mass(parameters_.handle_mass_kg + extra_handle_mass_kg, handle, &mass, &bias);
  out->mass = mass;
  out->bias_N_m = bias;
  out->handle_velocity_m_per_s = v;
  out->handle_bias_m_per_s2 = handle.bias_m_per_s2;
  return all_finite(bias) && std::isfinite(mass.m[0][0] + mass.m[0][1] + mass.m[1][0] + mass.m[1][1]);
}

// ---- The plant ----

PlanarPlant::PlanarPlant(const PlanarPlantParameters& parameters, const PlanarSimulationConfig& config)
    : parameters_(parameters),
      config_(config),
      model_(parameters, config.start_q_rad),
      hand_(config.hand, solve_linkage(parameters.linkage, config.start_q_rad).handle_m),
      noise_(config.noise_seed),
      q_rad_(config.start_q_rad),
      q_dot_rad_per_s_(config.start_q_dot_rad_per_s) {
  require(all_finite(config.start_q_dot_rad_per_s), "the start velocity must be finite");
  require(config.substeps_per_tick >= 1, "substeps per tick must be >= 1");
  pose_ = solve_linkage(parameters.linkage, q_rad_);
  for (int i = 0; i < 2; ++i) last_counts_[i] = parameters.sensor_min_counts[i];
}

void PlanarPlant::hold_motor_torques(const Vec2& motor_torque_N_m) noexcept {
  bool saturated = false;
  for (int i = 0; i < 2; ++i) {
    double torque = motor_torque_N_m[i];
    if (!std::isfinite(torque)) {
      ++command_faults_;
      torque = 0.0;
    }
    const double limit = parameters_.motor_torque_limit_N_m[i];
    if (std::abs(torque) > limit) {
      torque = std::copysign(limit, torque);
      saturated = true;
    }
    motor_torque_N_m_[i] = torque;
  }
  if (saturated) ++saturations_;
  const Matrix2& t = parameters_.motor_to_joint;
  joint_torque_N_m_ = Vec2{{t.m[0][0] * motor_torque_N_m_[0] + t.m[0][1] * motor_torque_N_m_[1],
                            t.m[1][0] * motor_torque_N_m_[0] + t.m[1][1] * motor_torque_N_m_[1]}};
}

void PlanarPlant::advance(double dt_s) noexcept {
  const int substeps = config_.substeps_per_tick;
  const double h_s = dt_s / substeps;
  for (int i = 0; i < substeps; ++i) substep(h_s);
}

// End stops: a spring-damper beyond each joint's range that pushes back and never pulls.
Vec2 PlanarPlant::stop_torque_N_m(const Vec2& q, const Vec2& q_dot) const noexcept {
  Vec2 torque{};
  for (int i = 0; i < 2; ++i) {
    const double k = parameters_.stop_stiffness_N_m_per_rad[i];
    const double c = parameters_.stop_damping_N_m_s_per_rad[i];
    if (q[i] < parameters_.stop_min_rad[i]) {
      torque[i] = std::max(0.0, k * (parameters_.stop_min_rad[i] - q[i]) - c * q_dot[i]);
    } else if (q[i] > parameters_.stop_max_rad[i]) {
      torque[i] = std::min(0.0, k * (parameters_.stop_max_rad[i] - q[i]) - c * q_dot[i]);
    }
  }
  return torque;
}

bool PlanarPlant::acceleration(double t_s, const Vec2& q, const Vec2& q_dot, const Friction& friction, Vec2* q_ddot,
                               Vec2* holding_N_m) const noexcept {
  const bool grip = hand_.gripping(t_s);
  PlanarDynamics d;
  if (!model_.evaluate(q, q_dot, grip ? hand_.config().mass_kg : 0.0, &d)) return false;
  Vec2 f = joint_torque_N_m_ + stop_torque_N_m(q, q_dot) - d.bias_N_m;
  for (int i = 0; i < 2; ++i) {
    f[i] -= parameters_.viscous_N_m_s_per_rad[i] * q_dot[i] + friction.direction[i] * parameters_.coulomb_N_m[i];
  }
  if (grip) f += joint_torques_N_m(d.pose.jacobian, hand_.force_N(t_s, d.pose.handle_m, d.handle_velocity_m_per_s));
  const Matrix2& m = d.mass;
  *holding_N_m = Vec2{};
  if (!friction.stuck[0] && !friction.stuck[1]) {
    const double det = m.m[0][0] * m.m[1][1] - m.m[0][1] * m.m[1][0];
    *q_ddot = Vec2{{(m.m[1][1] * f[0] - m.m[0][1] * f[1]) / det, (m.m[0][0] * f[1] - m.m[1][0] * f[0]) / det}};
  } else if (friction.stuck[0] && friction.stuck[1]) {
    *q_ddot = Vec2{};
    *holding_N_m = f;
  } else {
    // One joint held (k), the other free (j): M_jj q_ddot_j = f_j; the holding torque is
    // what is left on k after its share of j's acceleration.
    const int k = friction.stuck[0] ? 0 : 1;
    const int j = 1 - k;
    *q_ddot = Vec2{};
    (*q_ddot)[j] = f[j] / m.m[j][j];
    (*holding_N_m)[k] = f[k] - m.m[k][j] * (*q_ddot)[j];
  }
  return all_finite(*q_ddot) && all_finite(*holding_N_m);
}

// Breakaway at the substep's start: while a stuck joint's holding torque exceeds its
// Coulomb level, the one exceeding it most starts moving that way (this changes the
// other's holding torque, so it is checked again).
void PlanarPlant::settle_stuck_joints(double t_s, Friction* friction) const noexcept {
  for (int round = 0; round < 2; ++round) {
    if (!friction->stuck[0] && !friction->stuck[1]) return;
    Vec2 q_ddot{}, holding{};
    if (!acceleration(t_s, q_rad_, q_dot_rad_per_s_, *friction, &q_ddot, &holding)) return;
    int which = -1;
    double excess = 0.0;
    for (int i = 0; i < 2; ++i) {
      const double over = std::abs(holding[i]) - parameters_.coulomb_N_m[i];
      if (friction->stuck[i] && over > excess) {
        excess = over;
        which = i;
      }
    }
    if (which < 0) return;
    friction->stuck[which] = false;
    friction->direction[which] = sign_of(holding[which]);
  }
}

// The first and last stages look at the hand a hair inside the step (a millionth of it), so
// a jump of the hand's force on the step's boundary (where substep() puts every jump) is
// seen from the step's own side, not the neighbour's.
bool PlanarPlant::integrate(double t_s, double h_s, const Friction& friction) noexcept {
  const Vec2 q0 = q_rad_, v0 = q_dot_rad_per_s_;
  const double inside_s = 1e-6 * h_s;
  Vec2 a1{}, hold{};
  if (!acceleration(t_s + inside_s, q0, v0, friction, &a1, &hold)) return false;
  if (config_.integrator == PlanarIntegrator::semi_implicit_euler) {
    q_dot_rad_per_s_ = v0 + h_s * a1;
    q_rad_ = q0 + h_s * q_dot_rad_per_s_;
  } else {
    const double half = 0.5 * h_s;
    Vec2 a2{}, a3{}, a4{};
    const Vec2 v2 = v0 + half * a1;
    if (!acceleration(t_s + half, q0 + half * v0, v2, friction, &a2, &hold)) return false;
    const Vec2 v3 = v0 + half * a2;
    if (!acceleration(t_s + half, q0 + half * v2, v3, friction, &a3, &hold)) return false;
    const Vec2 v4 = v0 + h_s * a3;
    if (!acceleration(t_s + h_s - inside_s, q0 + h_s * v3, v4, friction, &a4, &hold)) return false;
    q_rad_ = q0 + (h_s / 6.0) * (v0 + 2.0 * v2 + 2.0 * v3 + v4);
    q_dot_rad_per_s_ = v0 + (h_s / 6.0) * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
  }
  for (int i = 0; i < 2; ++i) {
    if (friction.stuck[i]) q_dot_rad_per_s_[i] = 0.0;
  }
  pose_ = solve_linkage(parameters_.linkage, q_rad_);
  return pose_.valid && all_finite(q_dot_rad_per_s_);
}

// One substep, in passes that each end on the next discontinuity of the forces:
// - the hand's force jumps (a corner of its path, a waypoint, a release): known in advance,
//   the pass ends there;
// - Coulomb friction per joint, as the 1-D plant does on its one axis: the friction
//   directions and the stuck joints are fixed while integrating; when a moving joint's
//   velocity changes sign, or a stuck joint's holding torque passes its Coulomb level, the
//   pass is redone up to that moment (located linearly) and the joint stops (or starts);
// - a joint passing an end stop's edge: redone up to the crossing (located on the cubic
//   through the pass's ends).
// The rest of the substep follows from that state.
void PlanarPlant::substep(double h_s) noexcept {
  hand_.refresh_pointer();
  hand_force_N_ = hand_.force_N(t_s_, pose_.handle_m, handle_velocity_m_per_s());
  constexpr int kPasses = 10;
  double done_s = 0.0;
  double breakaway[2]{};
  for (int pass = 0; pass < kPasses && done_s < h_s; ++pass) {
    const double t_s = t_s_ + done_s;
    // A jump of the hand's force within the rest of the substep ends this pass there.
    const double rest_s = h_s - done_s;
    const double break_s = hand_.next_break_s(t_s + 1e-6 * rest_s) - t_s;
    const bool to_break = break_s < rest_s * (1.0 - 1e-6);
    const double tau_s = to_break ? break_s : rest_s;
    Friction friction;
    for (int i = 0; i < 2; ++i) {
      if (!(parameters_.coulomb_N_m[i] > 0.0)) continue;
      if (breakaway[i] != 0.0) friction.direction[i] = breakaway[i];
      else if (q_dot_rad_per_s_[i] != 0.0) friction.direction[i] = sign_of(q_dot_rad_per_s_[i]);
      else friction.stuck[i] = true;
    }
    breakaway[0] = breakaway[1] = 0.0;
    settle_stuck_joints(t_s + 1e-6 * tau_s, &friction);
    Vec2 q_ddot{}, hold_start{};
    const Vec2 q0 = q_rad_, v0 = q_dot_rad_per_s_;
    if (!acceleration(t_s + 1e-6 * tau_s, q0, v0, friction, &q_ddot, &hold_start) || !integrate(t_s, tau_s, friction)) {
      // Out of the linkage's range (or blown up): the joints stop where they were.
      ++linkage_faults_;
      q_rad_ = q0;
      q_dot_rad_per_s_ = Vec2{};
      pose_ = solve_linkage(parameters_.linkage, q_rad_);
      break;
    }
    if (pass + 1 == kPasses) {
      // Out of passes (many events in one substep): the rest is integrated without events.
      if (to_break && integrate(t_s + tau_s, rest_s - tau_s, friction)) done_s = h_s;
      break;
    }

    // The earliest event within the substep, as a fraction of it.
    double first = 1.0;
    int which = -1;
    enum class Event { reversal, break_away, stop_edge } event = Event::reversal;
    for (int i = 0; i < 2; ++i) {
      const double dir = friction.direction[i];
      if (dir == 0.0 || q_dot_rad_per_s_[i] * dir >= 0.0) continue;
      const double fraction = v0[i] * dir > 0.0 ? v0[i] / (v0[i] - q_dot_rad_per_s_[i]) : 0.0;
      if (fraction < first) {
        first = fraction;
        which = i;
        event = Event::reversal;
      }
    }
    // A joint passing an end stop's edge: the stop's force has a kink there (and a jump
    // where its damping engages), which costs an integrator its order unless the step ends on it.
    for (int i = 0; i < 2; ++i) {
      for (const double edge : {parameters_.stop_min_rad[i], parameters_.stop_max_rad[i]}) {
        const double before = q0[i] - edge, after = q_rad_[i] - edge;
        if (!std::isfinite(edge) || !(std::abs(before) > kOnEdge_rad) || before * after >= 0.0) continue;
        const double fraction =
            crossing_fraction(q0[i], v0[i] * tau_s, q_rad_[i], q_dot_rad_per_s_[i] * tau_s, edge);
        if (fraction < first) {
          first = fraction;
          which = i;
          event = Event::stop_edge;
        }
      }
    }
    Vec2 hold_end{};
    if (friction.stuck[0] || friction.stuck[1]) {
      if (!acceleration(t_s + tau_s * (1.0 - 1e-6), q_rad_, q_dot_rad_per_s_, friction, &q_ddot, &hold_end)) {
        hold_end = Vec2{};
      }
      for (int i = 0; i < 2; ++i) {
        const double c = parameters_.coulomb_N_m[i];
        if (!friction.stuck[i] || !(std::abs(hold_end[i]) > c)) continue;
        const double level = std::copysign(c, hold_end[i]);
        const double span = hold_end[i] - hold_start[i];
        const double fraction = span != 0.0 ? std::clamp((level - hold_start[i]) / span, 0.0, 1.0) : 0.0;
        if (fraction < first) {
          first = fraction;
          which = i;
          event = Event::break_away;
        }
      }
    }
    if (which < 0) {
      done_s = to_break ? done_s + tau_s : h_s;
      continue;
    }
    q_rad_ = q0;
    q_dot_rad_per_s_ = v0;
    pose_ = solve_linkage(parameters_.linkage, q_rad_);
    if (first > 0.0 && !integrate(t_s, first * tau_s, friction)) {
      ++linkage_faults_;
      q_rad_ = q0;
      q_dot_rad_per_s_ = Vec2{};
      pose_ = solve_linkage(parameters_.linkage, q_rad_);
      break;
    }
    if (event == Event::reversal) q_dot_rad_per_s_[which] = 0.0;
    else if (event == Event::break_away) breakaway[which] = sign_of(hold_end[which]);
    done_s += first * tau_s;
  }
  // Compensated sum of the clock (as in the 1-D plant).
  const double add_s = h_s - t_carry_s_;
  const double sum_s = t_s_ + add_s;
  t_carry_s_ = (sum_s - t_s_) - add_s;
  t_s_ = sum_s;
}

double PlanarPlant::kinetic_energy_J() const noexcept {
  PlanarDynamics d;
  if (!model_.evaluate(q_rad_, q_dot_rad_per_s_, 0.0, &d)) return 0.0;
  const Vec2& v = q_dot_rad_per_s_;
  return 0.5 * (d.mass.m[0][0] * v[0] * v[0] + (d.mass.m[0][1] + d.mass.m[1][0]) * v[0] * v[1] +
                d.mass.m[1][1] * v[1] * v[1]);
}

double PlanarPlant::stop_energy_J() const noexcept {
  double energy = 0.0;
  for (int i = 0; i < 2; ++i) {
    double depth = 0.0;
    if (q_rad_[i] < parameters_.stop_min_rad[i]) depth = parameters_.stop_min_rad[i] - q_rad_[i];
    else if (q_rad_[i] > parameters_.stop_max_rad[i]) depth = q_rad_[i] - parameters_.stop_max_rad[i];
    energy += 0.5 * parameters_.stop_stiffness_N_m_per_rad[i] * depth * depth;
  }
  return energy;
}

// Sensor: motor angle -> continuous counts (+ noise) -> nearest count -> wrapped (MR) or
// a 32-bit counter (encoder). An impossible reading is a counted fault.
std::array<std::int32_t, 2> PlanarPlant::sensor_counts() noexcept {
  const Matrix2& t = parameters_.motor_to_joint;
  for (int i = 0; i < 2; ++i) {
    const double motor_rad = t.m[0][i] * q_rad_[0] + t.m[1][i] * q_rad_[1];
    double counts = (motor_rad - parameters_.sensor_zero_rad[i]) / parameters_.sensor_step_rad[i];
    if (parameters_.sensor_noise_counts > 0.0) counts += parameters_.sensor_noise_counts * noise_.next();
    if (!(std::abs(counts) < 1e12)) {
      ++sensor_faults_;
      continue;
    }
    const auto quantized = static_cast<std::int64_t>(std::nearbyint(counts));
    const std::int64_t period = parameters_.sensor_period_counts[i];
    if (period > 0) {
      const std::int64_t low = parameters_.sensor_min_counts[i];
      std::int64_t within = (quantized - low) % period;
      if (within < 0) within += period;
      last_counts_[i] = static_cast<std::int32_t>(low + within);
    } else if (quantized < INT32_MIN || quantized > INT32_MAX) {
      ++sensor_faults_;
    } else {
      last_counts_[i] = static_cast<std::int32_t>(quantized);
    }
  }
  return last_counts_;
}

Vec2 motor_torques_for_joint_torques(const PlanarPlantParameters& parameters, const Vec2& joint_torque_N_m) noexcept {
  const Matrix2& t = parameters.motor_to_joint;
  const double det = t.m[0][0] * t.m[1][1] - t.m[0][1] * t.m[1][0];
  if (det == 0.0) return Vec2{};
  return Vec2{{(t.m[1][1] * joint_torque_N_m[0] - t.m[0][1] * joint_torque_N_m[1]) / det,
               (t.m[0][0] * joint_torque_N_m[1] - t.m[1][0] * joint_torque_N_m[0]) / det}};
}

// Newton's method on p(q) = target with the Jacobian, steps limited to 0.2 rad and halved
// while they leave the linkage's closable range.
bool joint_angles_for_handle(const Linkage& linkage, const Vec2& handle_m, const Vec2& guess_q_rad,
                             Vec2* q_rad) noexcept {
  if (!all_finite(handle_m) || !all_finite(guess_q_rad)) return false;
  Vec2 q = guess_q_rad;
  LinkagePose pose = solve_linkage(linkage, q);
  if (!pose.valid) return false;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Vec2 error = handle_m - pose.handle_m;
    if (norm(error) < 1e-9) {
      *q_rad = q;
      return true;
    }
    const Jacobian2& j = pose.jacobian;
    const double det = j.m[0][0] * j.m[1][1] - j.m[0][1] * j.m[1][0];
    if (det == 0.0) return false;
    Vec2 step{{(j.m[1][1] * error[0] - j.m[0][1] * error[1]) / det, (j.m[0][0] * error[1] - j.m[1][0] * error[0]) / det}};
    if (norm(step) > 0.2) step = step * (0.2 / norm(step));
    bool moved = false;
    for (int halving = 0; halving < 30; ++halving, step = 0.5 * step) {
      const LinkagePose next = solve_linkage(linkage, q + step);
      if (next.valid && norm(handle_m - next.handle_m) < norm(error)) {
        q = q + step;
        pose = next;
        moved = true;
        break;
      }
    }
    if (!moved) return false;
  }
  return false;
}

}  // namespace hapscene
