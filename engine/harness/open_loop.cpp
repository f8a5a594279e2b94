#include "engine/harness/open_loop.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/harness/pace.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// Two forces are the same when bit-equal or both NaN (a script is deterministic).
bool same_force(double a_N, double b_N) { return a_N == b_N || (std::isnan(a_N) && std::isnan(b_N)); }


}  // namespace

std::string describe_point(double x_m, double v_m_per_s, double t_s) {
  return printf_string("x %.2f mm, v %g m/s, t %g s", x_m * 1e3, v_m_per_s, t_s);
}

void ScriptFaultLog::add(const std::string& message, const std::string& where, double order_key) {
  insert(message, where.empty() ? message : message + " (first at " + where + ")", order_key);
}

void ScriptFaultLog::insert(const std::string& message, const std::string& line, double order_key) {
  const auto found = std::find(messages_.begin(), messages_.end(), message);
  if (found != messages_.end()) {
    // Seen before: keep the lowest point, so the line does not depend on the probing order.
    const auto i = static_cast<std::size_t>(found - messages_.begin());
    if (order_key < keys_[i]) {
      lines_[i] = line;
      keys_[i] = order_key;
      sort_by_key();
    }
    return;
  }
  if (messages_.size() < kMaxMessages) {
    messages_.push_back(message);
    lines_.push_back(line);
    keys_.push_back(order_key);
    sort_by_key();
    return;
  }
  // Full: keep the messages seen at the lowest keys (the same set whatever the order of
  // the calls), and count what is left out.
  omitted_ = true;
  const auto highest = std::max_element(keys_.begin(), keys_.end());
  if (order_key < *highest) {
    const auto i = static_cast<std::size_t>(highest - keys_.begin());
    messages_[i] = message;
    lines_[i] = line;
    keys_[i] = order_key;
    sort_by_key();
  }
}

void ScriptFaultLog::sort_by_key() {
  // At most kMaxMessages entries: sort the three lists together by (key, message).
  std::vector<std::size_t> order(messages_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return keys_[a] != keys_[b] ? keys_[a] < keys_[b] : messages_[a] < messages_[b];
  });
  std::vector<std::string> messages, lines;
  std::vector<double> keys;
  for (const std::size_t i : order) {
    messages.push_back(std::move(messages_[i]));
    lines.push_back(std::move(lines_[i]));
    keys.push_back(keys_[i]);
  }
  messages_ = std::move(messages);
  lines_ = std::move(lines);
  keys_ = std::move(keys);
}

void ScriptFaultLog::collect(const ScriptList& scripts, const std::string& where, double order_key) {
  for (const auto& script : scripts) {
    if (script->disabled()) add(std::string(script->fault_message()), where, order_key);
  }
}

void ScriptFaultLog::merge(const ScriptFaultLog& other) {
  for (std::size_t i = 0; i < other.messages_.size(); ++i) insert(other.messages_[i], other.lines_[i], other.keys_[i]);
  omitted_ = omitted_ || other.omitted_;
}

OpenLoop::OpenLoop(const Scene& scene, double t_s) : scene_(scene), t_s_(t_s), budget_(scene) {}

double OpenLoop::fresh_force_N(double x_m, double v_m_per_s, double t_s, bool record) {
  EffectInput input;
  input.x_m = x_m;
  input.v_m_per_s = v_m_per_s;
  input.t_s = t_s;
  input.dt_s = scene_.period_s;
  if (!has_scripts()) return sum_effects_N(scene_, input, none_);
  // New instances, each reset, as at the start of a run: nothing carries over.
  ScriptList scripts = create_instances();
  const double force_N = sum_effects_N(scene_, input, scripts);
  if (record) faults_.collect(scripts, describe_point(x_m, v_m_per_s, t_s), x_m);
  return force_N;
}

ScriptList OpenLoop::create_instances() {
  budget_.require(1);
  const double start_s = thread_cpu_time_s();
  ScriptList scripts = make_script_instances(scene_);
  budget_.charge(thread_cpu_time_s() - start_s);
  return scripts;
}

double OpenLoop::force_N(double x_m, double v_m_per_s) {
  budget_.set_points(1);
  return fresh_force_N(x_m, v_m_per_s, t_s_, true);
}

double OpenLoop::output_N(double x_m, double force_N) const {
  SafetyCounters counters;
  return apply_static_safety(scene_.safety, x_m, force_N, &counters);
}

template <int N>
std::vector<Axes<N>> reset_each_point_N(const SceneOf<N>& scene, ScriptList& scripts, const std::vector<Axes<N>>& x_m,
                                        const Axes<N>& v_m_per_s, double t_s, std::vector<bool>* live) {
  const std::size_t n = x_m.size();
  std::vector<Axes<N>> force_N(n);
  live->assign(n, true);
  bool faulted = false;
  EffectInputOf<N> input;
  input.v_m_per_s = v_m_per_s;
  input.t_s = t_s;
  input.dt_s = scene.period_s;
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& script : scripts) {
      script->reset();
      script->collect_garbage();
    }
    input.x_m = x_m[i];
    force_N[i] = sum_effects_N(scene, input, scripts);
    faulted = faulted || std::any_of(scripts.begin(), scripts.end(), [](const auto& s) { return s->disabled(); });
    (*live)[i] = !faulted;
  }
  return force_N;
}
template std::vector<Axes<1>> reset_each_point_N<1>(const SceneOf<1>&, ScriptList&, const std::vector<Axes<1>>&,
                                                    const Axes<1>&, double, std::vector<bool>*);
template std::vector<Axes<2>> reset_each_point_N<2>(const SceneOf<2>&, ScriptList&, const std::vector<Axes<2>>&,
                                                    const Axes<2>&, double, std::vector<bool>*);

std::vector<double> OpenLoop::sequential_N(const std::vector<double>& x_m, double v_m_per_s, bool upward,
                                           std::vector<bool>* live) {
  const std::size_t n = x_m.size();
  std::vector<double> force_N(n);
  live->assign(n, true);
  ScriptList scripts = create_instances();
  bool faulted = false;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = upward ? k : n - 1 - k;
    EffectInput input;
    input.x_m = x_m[i];
    input.v_m_per_s = v_m_per_s;
    input.t_s = t_s_;
    input.dt_s = scene_.period_s;
    force_N[i] = sum_effects_N(scene_, input, scripts);
    faulted = faulted || std::any_of(scripts.begin(), scripts.end(), [](const auto& s) { return s->disabled(); });
    (*live)[i] = !faulted;
  }
  return force_N;
}

void OpenLoop::scan_faults(const std::vector<double>& x_m, double v_m_per_s) {
  if (!has_scripts() || x_m.empty()) return;
  budget_.set_points(x_m.size());
  std::vector<bool> live;
  sequential_N(x_m, v_m_per_s, true, &live);
  if (live.back()) return;
  budget_.require(x_m.size());
  for (const double x : x_m) fresh_force_N(x, v_m_per_s, t_s_, true);
}

ScriptFaultLog scan_faults_in_motion(const Scene& scene, const std::vector<double>& x_m) {
  ScriptFaultLog faults;
  if (scene.script_count == 0) return faults;
  // One OpenLoop for every time and velocity: one creation budget for the whole search.
  OpenLoop open_loop(scene);
  for (const double t_s : kMotionScanTimes_s) {
    if (t_s != 0.0 && !scene.needs.time) continue;
    open_loop.set_time_s(t_s);
    for (const double v_m_per_s : kMotionScanVelocities_m_per_s) {
      if (v_m_per_s != 0.0 && !scene.needs.velocity) continue;
      open_loop.scan_faults(x_m, v_m_per_s);
      // The first velocity and time that meet a fault are reported: each further one
      // that faults would cost a fresh instance per point for what is mostly the same
      // message.
      if (!open_loop.faults().empty()) {
        faults.merge(open_loop.faults());
        return faults;
      }
    }
  }
  return faults;
}

OpenLoopScan OpenLoop::scan(const std::vector<double>& x_m, double v_m_per_s, bool values_if_not_static) {
  OpenLoopScan result;
  const std::size_t n = x_m.size();
  if (!has_scripts() || n == 0) {
    EffectInput input;
    input.v_m_per_s = v_m_per_s;
    input.t_s = t_s_;
    input.dt_s = scene_.period_s;
    for (const double x : x_m) {
      input.x_m = x;
      result.force_N.push_back(sum_effects_N(scene_, input, none_));
    }
    return result;
  }

  // State: one instance upwards, one downwards, fresh ones at up to 9 spread points.
  // Points after a script faulted are not compared (a disabled script answers 0).
  budget_.set_points(n);
  std::vector<bool> live_up;
  std::vector<bool> live_down;
  std::vector<double> up_N = sequential_N(x_m, v_m_per_s, true, &live_up);
  const std::size_t stride = std::max<std::size_t>(1, (n - 1) / 8);
  std::vector<std::size_t> spread;
  for (std::size_t i = 0; i < n; i += stride) spread.push_back(i);
  if (spread.back() != n - 1) spread.push_back(n - 1);
  // The creations the comparisons below need at most (the downward pass, and per spread
  // point one fresh instance, plus five at other times), now that one has been timed.
  budget_.require(1 + spread.size() * (scene_.needs.time ? 6 : 1));
  const std::vector<double> down_N = sequential_N(x_m, v_m_per_s, false, &live_down);
  bool faulted = false;
  for (std::size_t i = 0; i < n; ++i) {
    faulted = faulted || !live_up[i] || !live_down[i];
    if (live_up[i] && live_down[i] && !same_force(up_N[i], down_N[i])) result.behaviour.stateful = true;
  }
  for (const std::size_t i : spread) {
    if (result.behaviour.stateful) break;
    const double fresh_N = fresh_force_N(x_m[i], v_m_per_s, t_s_, false);
    if (live_up[i] && !same_force(fresh_N, up_N[i])) result.behaviour.stateful = true;
  }

  // Time: fresh instances at other run times, at the spread points.
  if (scene_.needs.time) {
    constexpr double kOtherTimes_s[] = {0.0137, 0.25, 0.7071, 1.9};
    for (const std::size_t i : spread) {
      if (result.behaviour.time_varying) break;
      const double at_t_N = fresh_force_N(x_m[i], v_m_per_s, t_s_, false);
      for (const double dt_s : kOtherTimes_s) {
        if (!same_force(fresh_force_N(x_m[i], v_m_per_s, t_s_ + dt_s, false), at_t_N)) {
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

  // The values: the upward pass when it is what fresh instances give.
  if (!faulted && !result.behaviour.stateful) {
    result.force_N = std::move(up_N);
    return result;
  }
  // State: one instance reset before each point, when nothing faulted and it gives what
  // fresh instances give at the spread points (the 2-D scan does the same); only when
  // that needs fewer creations than fresh instances at every point.
  if (!faulted && values_if_not_static && n > spread.size() + 1) {
    budget_.require(1 + spread.size());
    ScriptList scripts = create_instances();
    std::vector<bool> live_reset;
    std::vector<double> reset_N = reset_each_point_N(scene_, scripts, x_m, v_m_per_s, t_s_, &live_reset);
    bool agrees = live_reset.back();
    for (const std::size_t i : spread) {
      if (!agrees) break;
      agrees = same_force(fresh_force_N(x_m[i], v_m_per_s, t_s_, false), reset_N[i]);
    }
    if (agrees) {
      result.force_N = std::move(reset_N);
      return result;
    }
  }
  // Else every point from fresh instances.
  if (faulted || values_if_not_static) {
    budget_.require(n);
    result.force_N.resize(n);
    for (std::size_t i = 0; i < n; ++i) result.force_N[i] = fresh_force_N(x_m[i], v_m_per_s, t_s_, true);
  }
  return result;
}

}  // namespace hapscene
