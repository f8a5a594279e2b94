#include "engine/harness/planar_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "engine/base/format.hpp"
#include "engine/devices/planar/planar_model.hpp"
#include "engine/harness/metrics_parts.hpp"
#include "engine/harness/planar_script_potential.hpp"

namespace hapscene {
namespace {

// The energy a spring of stiffness K stores at stretch d when its force is clamped at
// limit_N (beyond d0 = limit / K the force stays at the limit).
double clamped_spring_J(double stiffness_N_per_m, double stretch_m, double limit_N) {
  if (!(stiffness_N_per_m > 0.0)) return 0.0;
  const double d0 = limit_N / stiffness_N_per_m;
  if (stretch_m <= d0) return 0.5 * stiffness_N_per_m * stretch_m * stretch_m;
  return 0.5 * stiffness_N_per_m * d0 * d0 + limit_N * (stretch_m - d0);
}

// The rendered springs' energy with the handle at x and the proxies of tick k, and the
// scripts' potential there (when given).
double stored_J(const PlanarScene& scene, const std::vector<PlanarShapeGeometry>& shapes,
                const std::vector<Vec2>& proxies_m, std::size_t k, const Vec2& x_m,
                const PlanarScriptPotential* scripts) {
  const double limit_N = scene.safety.max_force_N;
  double energy_J = 0.0;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const std::size_t at = k * shapes.size() + i;
    if (at >= proxies_m.size()) break;
    energy_J += clamped_spring_J(shapes[i].stiffness_N_per_m, norm(proxies_m[at] - x_m), limit_N);
  }
  for (const PlanarSpring& spring : scene.bank.group<PlanarSpring>()) {
    energy_J += clamped_spring_J(spring.stiffness_N_per_m, norm(x_m - spring.center_m), limit_N);
  }
  // Fields that declare a potential (a magnet), unclamped.
  std::apply(
      [&](const auto&... groups) {
        const auto add = [&](const auto& group) {
          for (const auto& e : group) {
            if constexpr (requires { e.potential_J(x_m); }) energy_J += e.potential_J(x_m);
          }
        };
        (add(groups), ...);
      },
      scene.bank.groups);
  if (scripts != nullptr) energy_J += scripts->at_J(x_m);
  return energy_J;
}

PassivityMetrics measure_passivity(const PlanarScene& scene, const std::vector<PlanarShapeGeometry>& shapes,
                                   const std::vector<PlanarValidateRecord>& records,
                                   const std::vector<Vec2>& proxies_m, const Vec2& final_q_rad,
                                   const PlanarScriptPotential* scripts) {
  PassivityMetrics p;
  const std::size_t n = records.size();
  if (n == 0) return p;
  const Vec2 b = scene.device.plant.viscous_N_m_s_per_rad;
  const Vec2 c = scene.device.plant.coulomb_N_m;
  const double period_s = scene.period_s;
  // The springs' stretch as the rendering sees it: from the measured handle.
  const double start_J = stored_J(scene, shapes, proxies_m, 0, records[0].x_m, scripts);
  double net_at_half_J = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 next_q = k + 1 < n ? records[k + 1].q_rad : final_q_rad;
    const Vec2 dq = next_q - records[k].q_rad;
    p.motor_work_J += dot(records[k].joint_torque_N_m, dq);
    if (records[k].joint_torque_N_m[0] != 0.0 || records[k].joint_torque_N_m[1] != 0.0) {
      // The joints' own losses: viscous, and Coulomb friction (what the 2fc/D bound rests on).
      p.dissipated_J += (b[0] * dq[0] * dq[0] + b[1] * dq[1] * dq[1]) / period_s;
      p.dissipated_J += c[0] * std::fabs(dq[0]) + c[1] * std::fabs(dq[1]);
    }
    if (k + 1 == n / 2) {
      const Vec2 next_x = records[k + 1].x_m;
      net_at_half_J = p.motor_work_J + stored_J(scene, shapes, proxies_m, k + 1, next_x, scripts) - start_J - p.dissipated_J;
    }
  }
  p.stored_J = stored_J(scene, shapes, proxies_m, n - 1, records[n - 1].x_m, scripts) - start_J;
  p.created_J = p.motor_work_J + p.stored_J;
  p.net_J = p.created_J - p.dissipated_J;
  p.ratio = p.dissipated_J > 0.0 ? p.created_J / p.dissipated_J : 0.0;
  p.grows = p.net_J > kMinJudgedEnergy_J && p.net_J > net_at_half_J;
  return p;
}

// The task-space length of one sensor count at joint angles q: the larger of the two
// joints' (|J column| x the joint's resolution).
double count_length_m(const PlanarScene& scene, const Vec2& q_rad) {
  const LinkagePose pose = solve_linkage(scene.device.linkage, q_rad);
  if (!pose.valid) return 0.0;
  const PlanarModel& model = scene.device_model.model;
  double length_m = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double column_m = std::hypot(pose.jacobian.m[0][i], pose.jacobian.m[1][i]);
    length_m = std::max(length_m, column_m * planar_joint_resolution_rad(model, i));
  }
  return length_m;
}

// Oscillation along the two principal axes of the motion in the window.
void measure_planar_oscillation(const PlanarScene& scene, const std::vector<PlanarValidateRecord>& records,
                                double from_s, PlanarScenarioMetrics* m) {
  const auto first = std::find_if(records.begin(), records.end(), [&](const auto& r) { return r.t_s >= from_s; });
  Vec2 mean{};
  std::size_t count = 0;
  for (auto it = first; it != records.end(); ++it, ++count) mean += it->x_true_m;
  if (count > 0) mean = mean / static_cast<double>(count);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (auto it = first; it != records.end(); ++it) {
    const Vec2 d = it->x_true_m - mean;
    sxx += d[0] * d[0];
    sxy += d[0] * d[1];
    syy += d[1] * d[1];
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const Vec2 major{{std::cos(angle), std::sin(angle)}};
  const Vec2 minor{{-major[1], major[0]}};
  const double band_m = 3.0 * count_length_m(scene, records.empty() ? Vec2{} : records.back().q_rad);
  std::vector<TickRecord> along_major;
  std::vector<TickRecord> along_minor;
  for (const PlanarValidateRecord& r : records) {
    TickRecord a;
    a.t_s = r.t_s;
    a.x_true_m = dot(r.x_true_m, major);
    along_major.push_back(a);
    a.x_true_m = dot(r.x_true_m, minor);
    along_minor.push_back(a);
  }
  OscillationMetrics o = measure_oscillation(along_major, from_s, band_m);
  const OscillationMetrics other = measure_oscillation(along_minor, from_s, band_m);
  o.residual_amplitude_m = std::max(o.residual_amplitude_m, other.residual_amplitude_m);
  o.initial_amplitude_m = std::max(o.initial_amplitude_m, other.initial_amplitude_m);
  o.growth = o.initial_amplitude_m > band_m ? o.residual_amplitude_m / o.initial_amplitude_m
             : o.residual_amplitude_m > band_m ? INFINITY : 0.0;
  m->rest_m = o.rest_m * major + other.rest_m * minor;
  o.rest_m = norm(m->rest_m);  // unused in 2-D; the vector is rest_m
  m->major_axis = major;
  m->oscillation = o;
}

// The unit normal out of the shape's solid at p: minus the gradient of the depth (at a
// point of the boundary, its normal; inside, toward the nearest boundary; outside, away).
Vec2 outward_normal(const PlanarShapeGeometry& shape, const Vec2& p_m) {
  constexpr double h = 1e-6;
  const Vec2 gradient{{(shape.depth_m(p_m + Vec2{{h, 0.0}}) - shape.depth_m(p_m - Vec2{{h, 0.0}})) / (2 * h),
                       (shape.depth_m(p_m + Vec2{{0.0, h}}) - shape.depth_m(p_m - Vec2{{0.0, h}})) / (2 * h)}};
  const double length = norm(gradient);
  return length > 0.0 ? -gradient / length : Vec2{};
}

}  // namespace

PlanarValidateRecorder::PlanarValidateRecorder(const SimulatedPlanar* device, std::size_t capacity,
                                               std::size_t shape_count, double period_s, std::atomic<bool>* stop)
    : shapes(shape_count), pace(period_s), device_(device), capacity_(capacity), stop_(stop) {
  records.reserve(capacity);
  proxies_m.reserve(capacity * shape_count);
}

void PlanarValidateRecorder::on_tick(const TickStateOf<2>& s) noexcept {
  if (records.size() < capacity_) {
    PlanarValidateRecord r;
    r.t_s = s.t_s;
    r.x_true_m = device_->x_m();
    r.x_m = s.x_m;
    r.q_rad = device_->plant().q_rad();
    r.joint_torque_N_m = device_->plant().joint_torque_N_m();
    r.requested_N = s.effects_force_N;
    r.output_N = s.output_N;
    r.hand_N = device_->hand_force_N();
    // The tick decides on a square-root-free test; the record keeps the number itself.
    r.condition = s.sensor.pose.valid ? condition_number(s.sensor.pose.jacobian) : INFINITY;
    r.pose_held = s.safety.counters.pose_hold_ticks != pose_holds_seen_;
    records.push_back(r);
    for (std::size_t i = 0; i < shapes; ++i) {
      proxies_m.push_back(i < s.effect_runs.size() ? s.effect_runs[i].proxy_m : s.x_m);
    }
  }
  pose_holds_seen_ = s.safety.counters.pose_hold_ticks;
  if (!pace.tick()) stop_->store(true, std::memory_order_relaxed);
}

void count_pop_throughs(const std::vector<PlanarShapeGeometry>& shapes,
                        const std::vector<PlanarValidateRecord>& records, const std::vector<Vec2>& proxies_m,
                        PlanarScenarioMetrics* m) {
  const std::size_t count = shapes.size();
  for (std::size_t i = 0; i < count; ++i) {
    const PlanarShapeGeometry& shape = shapes[i];
    const auto proxy_at = [&](std::size_t k) {
      const std::size_t at = k * count + i;
      return at < proxies_m.size() ? proxies_m[at] : records[k].x_true_m;
    };
    bool inside = false;
    Vec2 entry_out{};
    // A declared shape (a script's: no proxy) is judged by the direction of the scene's
    // requested force instead: the first and the latest nonzero while the handle is in.
    Vec2 first_pull{};
    Vec2 last_pull{};
    for (std::size_t k = 0; k < records.size(); ++k) {
      const Vec2& x = records[k].x_true_m;
      const bool now = shape.depth_m(x) > 0.0;
      if (now && !inside) {
        // Went in: the side of the solid the force pulls toward (its proxy's).
        if (!shape.declared) entry_out = outward_normal(shape, proxy_at(k));
        first_pull = Vec2{};
        last_pull = Vec2{};
      }
      if (now && shape.declared) {
        const double pull_N = norm(records[k].requested_N);
        if (pull_N > 0.0) {
          last_pull = records[k].requested_N / pull_N;
          if (!(norm(first_pull) > 0.0)) first_pull = last_pull;
        }
      }
      if (!now && inside) {
        // Came out: through the far side when the proxy is now across the solid (a
        // declared shape's: when the force last pulled across from where it first did).
        const double across = shape.declared ? dot(last_pull, first_pull)
                                             : dot(outward_normal(shape, proxy_at(k)), entry_out);
        if (across < -0.5) {
          if (m->pop_throughs == 0) {
            m->first_pop_x_m = x;
            m->first_pop_t_s = records[k].t_s;
            m->first_pop_shape = static_cast<int>(i);
          }
          ++m->pop_throughs;
        }
      }
      inside = now;
    }
  }
}

PlanarScenarioMetrics measure_planar_run(const PlanarScene& scene, const std::vector<PlanarShapeGeometry>& shapes,
                                         const std::vector<PlanarValidateRecord>& records,
                                         const std::vector<Vec2>& proxies_m, const Vec2& final_q_rad,
                                         const Vec2& final_x_m, const RunSummaryOf<2>& summary,
                                         std::optional<double> watch_from_s,
                                         const PlanarScriptPotential* script_potential) {
  PlanarScenarioMetrics m;
  m.ticks = records.size();
  m.duration_s = static_cast<double>(records.size()) * scene.period_s;
  measure_force_trace(records, scene.safety.max_force_N, scene.period_s, &m);
  // Shapes and singularity, tick by tick.
  for (std::size_t k = 0; k < records.size(); ++k) {
    const PlanarValidateRecord& r = records[k];
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      const double depth_m = shapes[i].depth_m(r.x_true_m);
      if (depth_m > m.max_penetration_m) {
        m.max_penetration_m = depth_m;
        m.max_penetration_x_m = r.x_true_m;
        m.max_penetration_t_s = r.t_s;
        m.max_penetration_shape = static_cast<int>(i);
      }
    }
    if (r.pose_held) {
      ++m.pose_hold_ticks;
      if (norm(r.requested_N) > 0.0) ++m.pose_hold_force_ticks;
    }
    if (k == 0 || r.condition > m.max_condition) {
      m.max_condition = r.condition;
      m.max_condition_x_m = r.x_true_m;
      m.max_condition_t_s = r.t_s;
    }
  }
  count_pop_throughs(shapes, records, proxies_m, &m);
  m.passivity = measure_passivity(scene, shapes, records, proxies_m, final_q_rad, script_potential);
  (void)final_x_m;
  if (watch_from_s) measure_planar_oscillation(scene, records, *watch_from_s, &m);

  measure_scripts_and_timing(summary, records, &m);
  return m;
}

}  // namespace hapscene
