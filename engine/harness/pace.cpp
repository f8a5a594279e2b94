#include "engine/harness/pace.hpp"

#include <ctime>

#include "engine/base/format.hpp"
#include "engine/harness/script_budget.hpp"
#include "engine/harness/stop_request.hpp"
#include "engine/scene/step.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene {

// "too slow for the 1000 Hz loop: force() took 48.2 ms of CPU time per call on average
// over the first 5 calls (the tick period is 1 ms)".
template <int N>
CheckResult pace_failure(const SceneOf<N>& scene, const char* what, const char* per, double cpu_s, std::uint64_t count,
                         const std::string& over) {
  const double average_s = cpu_s / static_cast<double>(count);
  CheckResult check;
  check.name = "pace";
  check.value = average_s;
  check.threshold = scene.period_s;
  check.unit = "s";
  check.pass = false;
  check.detail = printf_string("too slow for the %g Hz loop: %s took %.3g ms of CPU time per %s on average over %s "
                               "(the tick period is %g ms)",
                               scene.rate_hz, what, average_s * 1e3, per, over.c_str(), scene.period_s * 1e3);
  return check;
}
#define HAPSCENE_PACE_FAILURE(N)                                                                 \
  template CheckResult pace_failure<N>(const SceneOf<N>&, const char*, const char*, double, std::uint64_t, \
                                       const std::string&);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_PACE_FAILURE)
#undef HAPSCENE_PACE_FAILURE

double thread_cpu_time_s() noexcept {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

namespace {

// The scripts' calls along the workspace: in 1-D from its low to its high end, in 2-D
// along the diagonal of its box.
template <int N>
std::optional<CheckResult> check_script_pace_of(const SceneOf<N>& scene) {
  if (scene.script_count == 0) return std::nullopt;
  ScriptList scripts = make_script_instances(scene);
  const double allowed_s = static_cast<double>(kPaceWindowCalls) * scene.period_s;
  const Axes<N> span_m = scene.safety.workspace_max_m - scene.safety.workspace_min_m;
  EffectInputOf<N> input;
  input.dt_s = scene.period_s;
  double cpu_s = 0.0;
  for (std::uint64_t k = 0; k < kPaceWindowCalls; ++k) {
    input.x_m = scene.safety.workspace_min_m + span_m * (static_cast<double>(k) + 0.5) / static_cast<double>(kPaceWindowCalls);
    input.t_s = static_cast<double>(k) * scene.period_s;
    throw_if_stop_requested();
    const double start_s = thread_cpu_time_s();
    sum_effects_N(scene, input, scripts);
    cpu_s += thread_cpu_time_s() - start_s;
    if (cpu_s > allowed_s) {
      return pace_failure(scene, "force()", "call", cpu_s, k + 1,
                          printf_string("the first %llu calls", static_cast<unsigned long long>(k + 1)));
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<CheckResult> check_script_pace(const Scene& scene) { return check_script_pace_of(scene); }
std::optional<CheckResult> check_script_pace(const PlanarScene& scene) { return check_script_pace_of(scene); }

bool PaceWatch::tick() noexcept {
  if (too_slow_ || stop_requested()) return false;
  if (window_start_s_ < 0.0) window_start_s_ = thread_cpu_time_s();
  ++ticks_;
  ++window_ticks_;
  if (window_ticks_ % kPaceCheckEvery != 0 && window_ticks_ != kPaceWindowCalls) return true;
  const double used_s = thread_cpu_time_s() - window_start_s_;
  if (used_s > static_cast<double>(kPaceWindowCalls) * period_s_) {
    too_slow_ = true;
    measured_s_ = used_s;
    measured_ticks_ = window_ticks_;
    measured_from_tick_ = ticks_ - window_ticks_;
    return false;
  }
  if (window_ticks_ == kPaceWindowCalls) {
    window_ticks_ = 0;
    window_start_s_ = thread_cpu_time_s();
  }
  return true;
}

CheckResult PaceWatch::check(const Scene& scene) const {
  return pace_failure(scene, "the run's ticks", "tick", measured_s_, measured_ticks_,
                      printf_string("the %llu ticks from t = %g s", static_cast<unsigned long long>(measured_ticks_),
                                    static_cast<double>(measured_from_tick_) * period_s_));
}

bool ScanPace::charge(double cpu_s, std::uint64_t calls) noexcept {
  if (too_slow_) return false;
  window_s_ += cpu_s;
  window_calls_ += calls;
  calls_ += calls;
  const double window_allows_s = static_cast<double>(kPaceWindowCalls) * allowed_per_call_s_;
  if (window_s_ > window_allows_s ||
      (window_calls_ >= kPaceWindowCalls && window_s_ > static_cast<double>(window_calls_) * allowed_per_call_s_)) {
    too_slow_ = true;
    return false;
  }
  if (window_calls_ >= kPaceWindowCalls) {
    window_s_ = 0.0;
    window_calls_ = 0;
  }
  return true;
}

template <int N>
CheckResult ScanPace::check(const SceneOf<N>& scene) const {
  const std::uint64_t before = calls_ - window_calls_;
  const std::string over =
      (before == 0 ? printf_string("the first %llu calls of an open-loop scan",
                                   static_cast<unsigned long long>(window_calls_))
                   : printf_string("%llu calls of an open-loop scan after its first %llu",
                                   static_cast<unsigned long long>(window_calls_),
                                   static_cast<unsigned long long>(before))) +
      printf_string(", above the %g ms a call (%g of the tick period) the harness's scans allow a script, as they call "
                    "it thousands of times",
                    allowed_per_call_s_ * 1e3, kScanPaceShare);
  CheckResult check = pace_failure(scene, (script_names(scene) + ": force()").c_str(), "call", window_s_,
                                   window_calls_, over);
  check.threshold = allowed_per_call_s_;
  return check;
}
#define HAPSCENE_SCAN_PACE(N) template CheckResult ScanPace::check<N>(const SceneOf<N>&) const;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_SCAN_PACE)
#undef HAPSCENE_SCAN_PACE

}  // namespace hapscene
