#include "engine/harness/open_loop.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/stop_request.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// Two forces are the same when bit-equal or both NaN on each axis (a script is
// deterministic).
bool same_force(double a_N, double b_N) { return a_N == b_N || (std::isnan(a_N) && std::isnan(b_N)); }
bool same_force(const Vec2& a_N, const Vec2& b_N) { return same_force(a_N[0], b_N[0]) && same_force(a_N[1], b_N[1]); }

// Charges `calls` calls of the scripts that took `cpu_s` to the scan's pace, between
// calls: the evaluation ends with ScriptsTooSlow when they are too slow for the loop's
// checks, or with CheckInterrupted when its thread was asked to stop.
template <int N>
void charge_calls(const SceneOf<N>& scene, ScanPace* pace, double cpu_s, std::uint64_t calls) {
  throw_if_stop_requested();
  if (!pace->charge(cpu_s, calls)) throw ScriptsTooSlow(pace->check(scene));
}

// One instance per script in `scripts` called at each point of `x_m` (in order, or in
// reverse when not `forward`; reset() before each call when `reset_each`) at velocity v
// and run time t. `live[i]` is false where a script had faulted before or at that call.
// The calls are charged to `pace`: the clock is read every kCallsPerClockRead calls, or
// around each call when a reset() and a collection (not calls) come between them.
template <int N>
std::vector<Axes<N>> call_at_points_N(const SceneOf<N>& scene, ScriptList& scripts, const std::vector<Axes<N>>& x_m,
                                      const Axes<N>& v_m_per_s, double t_s, bool forward, bool reset_each,
                                      ScanPace* pace, std::vector<bool>* live) {
  constexpr std::size_t kCallsPerClockRead = 16;
  const std::size_t n = x_m.size();
  std::vector<Axes<N>> force_N(n);
  live->assign(n, true);
  bool faulted = false;
  EffectInputOf<N> input;
  input.v_m_per_s = v_m_per_s;
  input.t_s = t_s;
  input.dt_s = scene.period_s;
  double block_start_s = thread_cpu_time_s();
  std::uint64_t block_calls = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = forward ? k : n - 1 - k;
    if (reset_each) {
      for (const auto& script : scripts) {
        script->reset();
        script->collect_garbage();
      }
      block_start_s = thread_cpu_time_s();
    }
    input.x_m = x_m[i];
    force_N[i] = sum_effects_N(scene, input, scripts);
    ++block_calls;
    if (reset_each || block_calls == kCallsPerClockRead || k + 1 == n) {
      const double now_s = thread_cpu_time_s();
      charge_calls(scene, pace, now_s - block_start_s, block_calls);
      block_start_s = now_s;
      block_calls = 0;
    }
    faulted = faulted || std::any_of(scripts.begin(), scripts.end(), [](const auto& s) { return s->disabled(); });
    (*live)[i] = !faulted;
  }
  return force_N;
}

}  // namespace

std::string describe_point(double x_m, double v_m_per_s, double t_s) {
  return printf_string("x %.2f mm, v %g m/s, t %g s", x_m * 1e3, v_m_per_s, t_s);
}

std::string describe_point(const Vec2& x_m, const Vec2& v_m_per_s, double t_s) {
  return printf_string("x %.2f mm, y %.2f mm, v (%g, %g) m/s, t %g s", x_m[0] * 1e3, x_m[1] * 1e3, v_m_per_s[0],
                       v_m_per_s[1], t_s);
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

std::vector<std::string> ScriptFaultLog::report_lines(std::string_view among) const {
  std::vector<std::string> out = lines_;
  if (omitted_) {
    out.push_back("... and script faults with other messages (only the " + std::to_string(kMaxMessages) + " first" +
                  (among.empty() ? std::string() : " " + std::string(among)) + " are shown)");
  }
  return out;
}

void ScriptFaultLog::merge(const ScriptFaultLog& other) {
  for (std::size_t i = 0; i < other.messages_.size(); ++i) insert(other.messages_[i], other.lines_[i], other.keys_[i]);
  omitted_ = omitted_ || other.omitted_;
}

template <int N>
OpenLoopOf<N>::OpenLoopOf(const SceneOf<N>& scene, double t_s)
    : scene_(scene), t_s_(t_s), budget_(scene), pace_(scene.period_s) {}

template <int N>
Axes<N> OpenLoopOf<N>::fresh_force_N(const Axes<N>& x_m, const Axes<N>& v_m_per_s, double t_s, bool record,
                                     double order_key, bool* faulted) {
  EffectInputOf<N> input;
  input.x_m = x_m;
  input.v_m_per_s = v_m_per_s;
  input.t_s = t_s;
  input.dt_s = scene_.period_s;
  if (!has_scripts()) return sum_effects_N(scene_, input, none_);
  // New instances, each reset, as at the start of a run: nothing carries over.
  ScriptList scripts = create_instances();
  const double start_s = thread_cpu_time_s();
  const Axes<N> force_N = sum_effects_N(scene_, input, scripts);
  charge_calls(scene_, &pace_, thread_cpu_time_s() - start_s, 1);
  if (record) faults_.collect(scripts, describe_point(x_m, v_m_per_s, t_s), order_key);
  if (faulted != nullptr) {
    *faulted = std::any_of(scripts.begin(), scripts.end(), [](const auto& script) { return script->disabled(); });
  }
  return force_N;
}

template <int N>
ScriptList OpenLoopOf<N>::create_instances() {
  throw_if_stop_requested();
  budget_.require(1);
  const double start_s = thread_cpu_time_s();
  ScriptList scripts = make_script_instances(scene_);
  budget_.charge(thread_cpu_time_s() - start_s);
  return scripts;
}

template <int N>
Axes<N> OpenLoopOf<N>::force_N(const Axes<N>& x_m, const Axes<N>& v_m_per_s) {
  budget_.set_points(1);
  return fresh_force_N(x_m, v_m_per_s, t_s_, true, point_order_key(x_m, 0));
}

template <int N>
Axes<N> OpenLoopOf<N>::output_N(const Axes<N>& x_m, const Axes<N>& force_N) const {
  SafetyCounters counters;
  return apply_static_safety(scene_.safety, x_m, force_N, &counters);
}

template <int N>
std::vector<Axes<N>> reset_each_point_N(const SceneOf<N>& scene, ScriptList& scripts, const std::vector<Axes<N>>& x_m,
                                        const Axes<N>& v_m_per_s, double t_s, ScanPace* pace,
                                        std::vector<bool>* live) {
  return call_at_points_N(scene, scripts, x_m, v_m_per_s, t_s, true, true, pace, live);
}
#define HAPSCENE_RESET_EACH_POINT(N)                                                                \
  template std::vector<Axes<N>> reset_each_point_N<N>(const SceneOf<N>&, ScriptList&, const std::vector<Axes<N>>&, \
                                                      const Axes<N>&, double, ScanPace*, std::vector<bool>*);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_RESET_EACH_POINT)
#undef HAPSCENE_RESET_EACH_POINT

template <int N>
std::vector<Axes<N>> OpenLoopOf<N>::sequential_N(const std::vector<Axes<N>>& x_m, const Axes<N>& v_m_per_s,
                                                 bool forward, std::vector<bool>* live) {
  ScriptList scripts = create_instances();
  return call_at_points_N(scene_, scripts, x_m, v_m_per_s, t_s_, forward, false, &pace_, live);
}

template <int N>
void OpenLoopOf<N>::scan_faults(const std::vector<Axes<N>>& x_m, const Axes<N>& v_m_per_s) {
  if (!has_scripts() || x_m.empty()) return;
  budget_.set_points(x_m.size());
  std::vector<bool> live;
  sequential_N(x_m, v_m_per_s, true, &live);
  if (live.back()) return;
  budget_.require(x_m.size());
  for (std::size_t i = 0; i < x_m.size(); ++i) fresh_force_N(x_m[i], v_m_per_s, t_s_, true, point_order_key(x_m[i], i));
}

template <>
std::vector<double> motion_scan_velocities<1>() {
  return {std::begin(kMotionScanVelocities_m_per_s), std::end(kMotionScanVelocities_m_per_s)};
}

template <>
std::vector<Vec2> motion_scan_velocities<2>() {
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

template <int N>
ScriptFaultLog scan_faults_in_motion(const SceneOf<N>& scene, const std::vector<Axes<N>>& x_m) {
  ScriptFaultLog faults;
  if (scene.script_count == 0) return faults;
  // One open loop for every time and velocity: one creation budget for the whole search.
  OpenLoopOf<N> open_loop(scene);
  for (const double t_s : kMotionScanTimes_s) {
    if (t_s != 0.0 && !scene.needs.time) continue;
    open_loop.set_time_s(t_s);
    for (const Axes<N>& v_m_per_s : motion_scan_velocities<N>()) {
      if (norm(v_m_per_s) != 0.0 && !scene.needs.velocity) continue;
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

template <int N>
OpenLoopScanOf<N> OpenLoopOf<N>::scan(const std::vector<Axes<N>>& x_m, const Axes<N>& v_m_per_s,
                                       bool values_if_not_static) {
  OpenLoopScanOf<N> result;
  const std::size_t n = x_m.size();
  if (!has_scripts() || n == 0) {
    EffectInputOf<N> input;
    input.v_m_per_s = v_m_per_s;
    input.t_s = t_s_;
    input.dt_s = scene_.period_s;
    for (const Axes<N>& x : x_m) {
      input.x_m = x;
      result.force_N.push_back(sum_effects_N(scene_, input, none_));
    }
    return result;
  }

  // State: one instance forwards, one backwards, fresh ones at up to 9 spread points.
  // Points after a script faulted are not compared (a disabled script answers 0).
  budget_.set_points(n);
  std::vector<bool> live_forward;
  std::vector<bool> live_backward;
  std::vector<Axes<N>> forward_N = sequential_N(x_m, v_m_per_s, true, &live_forward);
  const std::size_t stride = std::max<std::size_t>(1, (n - 1) / 8);
  std::vector<std::size_t> spread;
  for (std::size_t i = 0; i < n; i += stride) spread.push_back(i);
  if (spread.back() != n - 1) spread.push_back(n - 1);
  // The creations the comparisons below need at most (the backward pass, and per spread
  // point one fresh instance, plus five at other times), now that one has been timed.
  budget_.require(1 + spread.size() * (scene_.needs.time ? 6 : 1));
  const std::vector<Axes<N>> backward_N = sequential_N(x_m, v_m_per_s, false, &live_backward);
  bool faulted = false;
  for (std::size_t i = 0; i < n; ++i) {
    faulted = faulted || !live_forward[i] || !live_backward[i];
    if (live_forward[i] && live_backward[i] && !same_force(forward_N[i], backward_N[i])) result.behaviour.stateful = true;
  }
  for (const std::size_t i : spread) {
    if (result.behaviour.stateful) break;
    const Axes<N> fresh_N = fresh_force_N(x_m[i], v_m_per_s, t_s_, false, 0.0);
    if (live_forward[i] && !same_force(fresh_N, forward_N[i])) result.behaviour.stateful = true;
  }

  // Time: fresh instances at other run times, at the spread points.
  if (scene_.needs.time) {
    constexpr double kOtherTimes_s[] = {0.0137, 0.25, 0.7071, 1.9};
    for (const std::size_t i : spread) {
      if (result.behaviour.time_varying) break;
      const Axes<N> at_t_N = fresh_force_N(x_m[i], v_m_per_s, t_s_, false, 0.0);
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
  // State: one instance reset before each point, when nothing faulted and it gives what
  // fresh instances give at the spread points (the maze's proxy); only when that needs
  // fewer creations than fresh instances at every point.
  if (!faulted && values_if_not_static && n > spread.size() + 1) {
    budget_.require(1 + spread.size());
    ScriptList scripts = create_instances();
    std::vector<bool> live_reset;
    std::vector<Axes<N>> reset_N = reset_each_point_N(scene_, scripts, x_m, v_m_per_s, t_s_, &pace_, &live_reset);
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
  if (faulted || values_if_not_static) {
    budget_.require(n);
    result.force_N.resize(n);
    result.script_faulted.assign(n, false);
    for (std::size_t i = 0; i < n; ++i) {
      bool faulted_here = false;
      result.force_N[i] = fresh_force_N(x_m[i], v_m_per_s, t_s_, true, point_order_key(x_m[i], i), &faulted_here);
      result.script_faulted[i] = faulted_here;
    }
    if (std::none_of(result.script_faulted.begin(), result.script_faulted.end(), [](bool f) { return f; })) {
      result.script_faulted.clear();
    }
  }
  return result;
}

#define HAPSCENE_OPEN_LOOP(N) \
  template class OpenLoopOf<N>; \
  template ScriptFaultLog scan_faults_in_motion<N>(const SceneOf<N>&, const std::vector<Axes<N>>&);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_OPEN_LOOP)
#undef HAPSCENE_OPEN_LOOP

}  // namespace hapscene
