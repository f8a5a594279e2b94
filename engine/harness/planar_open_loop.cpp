#include "engine/harness/planar_open_loop.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/format.hpp"
#include "engine/harness/pace.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// Bit-equal, or both NaN, on each axis (a script is deterministic).
bool same_force(const Vec2& a_N, const Vec2& b_N) {
  for (int i = 0; i < 2; ++i) {
    if (!(a_N[i] == b_N[i] || (std::isnan(a_N[i]) && std::isnan(b_N[i])))) return false;
  }
  return true;
}

}  // namespace

std::string describe_planar_point(const Vec2& x_m, const Vec2& v_m_per_s, double t_s) {
  return printf_string("x %.2f mm, y %.2f mm, v (%g, %g) m/s, t %g s", x_m[0] * 1e3, x_m[1] * 1e3, v_m_per_s[0],
                       v_m_per_s[1], t_s);
}

PlanarOpenLoop::PlanarOpenLoop(const PlanarScene& scene, double t_s) : scene_(scene), t_s_(t_s), budget_(scene) {}

ScriptList PlanarOpenLoop::create_instances() {
  budget_.require(1);
  const double start_s = thread_cpu_time_s();
  ScriptList scripts = make_script_instances(scene_);
  budget_.charge(thread_cpu_time_s() - start_s);
  return scripts;
}

Vec2 PlanarOpenLoop::fresh_force_N(const Vec2& x_m, const Vec2& v_m_per_s, double t_s, bool record,
                                   double order_key) {
  EffectInputOf<2> input;
  input.x_m = x_m;
  input.v_m_per_s = v_m_per_s;
  input.t_s = t_s;
  input.dt_s = scene_.period_s;
  if (!has_scripts()) return sum_effects_N(scene_, input, none_);
  // New instances, each reset, as at the start of a run: nothing carries over.
  ScriptList scripts = create_instances();
  const Vec2 force_N = sum_effects_N(scene_, input, scripts);
  if (record) faults_.collect(scripts, describe_planar_point(x_m, v_m_per_s, t_s), order_key);
  return force_N;
}

Vec2 PlanarOpenLoop::force_N(const Vec2& x_m, const Vec2& v_m_per_s, double order_key) {
  budget_.set_points(1);
  return fresh_force_N(x_m, v_m_per_s, t_s_, true, order_key);
}

Vec2 PlanarOpenLoop::output_N(const Vec2& x_m, const Vec2& force_N) const {
  SafetyCounters counters;
  return apply_static_safety(scene_.safety, x_m, force_N, &counters);
}

std::vector<Vec2> PlanarOpenLoop::sequential_N(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s, bool forward,
                                               std::vector<bool>* live) {
  const std::size_t n = x_m.size();
  std::vector<Vec2> force_N(n);
  live->assign(n, true);
  ScriptList scripts = create_instances();
  bool faulted = false;
  EffectInputOf<2> input;
  input.v_m_per_s = v_m_per_s;
  input.t_s = t_s_;
  input.dt_s = scene_.period_s;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = forward ? k : n - 1 - k;
    input.x_m = x_m[i];
    force_N[i] = sum_effects_N(scene_, input, scripts);
    faulted = faulted || std::any_of(scripts.begin(), scripts.end(), [](const auto& s) { return s->disabled(); });
    (*live)[i] = !faulted;
  }
  return force_N;
}

std::vector<Vec2> PlanarOpenLoop::reset_each_N(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s,
                                               std::vector<bool>* live) {
  ScriptList scripts = create_instances();
  return reset_each_point_N(scene_, scripts, x_m, v_m_per_s, t_s_, live);
}

void PlanarOpenLoop::scan_faults(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s) {
  if (!has_scripts() || x_m.empty()) return;
  budget_.set_points(x_m.size());
  std::vector<bool> live;
  sequential_N(x_m, v_m_per_s, true, &live);
  if (live.back()) return;
  budget_.require(x_m.size());
  for (std::size_t i = 0; i < x_m.size(); ++i) fresh_force_N(x_m[i], v_m_per_s, t_s_, true, static_cast<double>(i));
}

PlanarOpenLoopScan PlanarOpenLoop::scan(const std::vector<Vec2>& x_m, const Vec2& v_m_per_s) {
  PlanarOpenLoopScan result;
  const std::size_t n = x_m.size();
  if (!has_scripts() || n == 0) {
    EffectInputOf<2> input;
    input.v_m_per_s = v_m_per_s;
    input.t_s = t_s_;
    input.dt_s = scene_.period_s;
    for (const Vec2& x : x_m) {
      input.x_m = x;
      result.force_N.push_back(sum_effects_N(scene_, input, none_));
    }
    return result;
  }

  // State: one instance forwards, one backwards, fresh ones at up to 9 spread points
  // (after a script faulted, points are not compared: a disabled script answers 0).
  budget_.set_points(n);
  std::vector<bool> live_forward;
  std::vector<bool> live_backward;
  std::vector<Vec2> forward_N = sequential_N(x_m, v_m_per_s, true, &live_forward);
  const std::size_t stride = std::max<std::size_t>(1, (n - 1) / 8);
  std::vector<std::size_t> spread;
  for (std::size_t i = 0; i < n; i += stride) spread.push_back(i);
  if (spread.back() != n - 1) spread.push_back(n - 1);
  budget_.require(1 + spread.size() * (scene_.needs.time ? 6 : 1));
  const std::vector<Vec2> backward_N = sequential_N(x_m, v_m_per_s, false, &live_backward);
  bool faulted = false;
  for (std::size_t i = 0; i < n; ++i) {
    faulted = faulted || !live_forward[i] || !live_backward[i];
    if (live_forward[i] && live_backward[i] && !same_force(forward_N[i], backward_N[i])) {
      result.behaviour.stateful = true;
    }
  }
  for (const std::size_t i : spread) {
    if (result.behaviour.stateful) break;
    const Vec2 fresh_N = fresh_force_N(x_m[i], v_m_per_s, t_s_, false, 0.0);
    if (live_forward[i] && !same_force(fresh_N, forward_N[i])) result.behaviour.stateful = true;
  }
  // Time: fresh instances at other run times, at the spread points.
  if (scene_.needs.time) {
    constexpr double kOtherTimes_s[] = {0.0137, 0.25, 0.7071, 1.9};
    for (const std::size_t i : spread) {
      if (result.behaviour.time_varying) break;
      const Vec2 at_t_N = fresh_force_N(x_m[i], v_m_per_s, t_s_, false, 0.0);
      for (const double dt_s : kOtherTimes_s) {
        if (!same_force(fresh_force_N(x_m[i], v_m_per_s, t_s_ + dt_s, false, 0.0), at_t_N)) {
          result.behaviour.time_varying = true;
          break;
        }
      }
    }
  }
  if (!result.behaviour.static_field()) {
    const ScriptBehaviour& b = result.behaviour;
    result.behaviour.note = script_names(scene_) + " " +
                            (b.stateful && b.time_varying ? "keeps state between calls and reads time"
                             : b.stateful                 ? "keeps state between calls"
                                                          : "reads time") +
                            ": not a fixed force field";
  }

  // The values: the forward pass when it is what fresh instances give.
  if (!faulted && !result.behaviour.stateful) {
    result.force_N = std::move(forward_N);
    return result;
  }
  // State: one instance reset before each point gives what fresh ones give when the
  // script's reset() restores all its state (the maze's proxy); checked against fresh
  // instances at the spread points, and used only when nothing faulted and all agree
  // (and when that needs fewer creations than fresh instances at every point).
  if (!faulted && n > spread.size() + 1) {
    budget_.require(1 + spread.size());
    std::vector<bool> live_reset;
    std::vector<Vec2> reset_N = reset_each_N(x_m, v_m_per_s, &live_reset);
    bool agrees = live_reset.back();
    for (const std::size_t i : spread) {
      if (!agrees) break;
      agrees = same_force(fresh_force_N(x_m[i], v_m_per_s, t_s_, false, 0.0), reset_N[i]);
    }
    if (agrees) {
      result.force_N = std::move(reset_N);
      return result;
    }
  }
  // Else every point from fresh instances.
  budget_.require(n);
  result.force_N.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    result.force_N[i] = fresh_force_N(x_m[i], v_m_per_s, t_s_, true, static_cast<double>(i));
  }
  return result;
}

std::vector<Vec2> planar_workspace_grid(const PlanarScene& scene, double step_m) {
  const Vec2& low = scene.safety.workspace_min_m;
  const Vec2& high = scene.safety.workspace_max_m;
  const auto count = [&](int axis) {
    return static_cast<std::size_t>(std::floor((high[axis] - low[axis]) / step_m + 1e-9)) + 1;
  };
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < count(0); ++i) {
    for (std::size_t j = 0; j < count(1); ++j) {
      const Vec2 p{{low[0] + static_cast<double>(i) * step_m, low[1] + static_cast<double>(j) * step_m}};
      if (within_workspace(scene.safety, p)) points.push_back(p);
    }
  }
  return points;
}

std::vector<Vec2> planar_motion_scan_velocities() {
  std::vector<Vec2> velocities{Vec2{}};
  for (const double speed : kMotionScanVelocities_m_per_s) {
    if (speed <= 0.0) continue;  // each speed once, in all four directions
    velocities.push_back(Vec2{{speed, 0.0}});
    velocities.push_back(Vec2{{-speed, 0.0}});
    velocities.push_back(Vec2{{0.0, speed}});
    velocities.push_back(Vec2{{0.0, -speed}});
  }
  return velocities;
}

ScriptFaultLog scan_planar_faults_in_motion(const PlanarScene& scene, const std::vector<Vec2>& x_m) {
  ScriptFaultLog faults;
  if (scene.script_count == 0) return faults;
  // One PlanarOpenLoop for every time and velocity: one creation budget for the search.
  PlanarOpenLoop open_loop(scene);
  for (const double t_s : kMotionScanTimes_s) {
    if (t_s != 0.0 && !scene.needs.time) continue;
    open_loop.set_time_s(t_s);
    for (const Vec2& v_m_per_s : planar_motion_scan_velocities()) {
      if (norm(v_m_per_s) != 0.0 && !scene.needs.velocity) continue;
      open_loop.scan_faults(x_m, v_m_per_s);
      if (!open_loop.faults().empty()) {
        faults.merge(open_loop.faults());
        return faults;
      }
    }
  }
  return faults;
}

}  // namespace hapscene
