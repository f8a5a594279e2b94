#include "engine/cli/run_summary.hpp"

#include <cstdio>
#include <string>

#include "engine/base/format.hpp"
#include "engine/cli/standard_output.hpp"

namespace hapscene {
namespace {

double us(std::uint64_t ns) { return static_cast<double>(ns) * 1e-3; }
unsigned long long count(std::uint64_t n) { return static_cast<unsigned long long>(n); }

// A bound's name for axis i: "workspace min" with one axis, "workspace min x" with more.
std::string axis_name(const char* name, int axes, int i) {
  return axes == 1 ? std::string(name) : std::string(name) + (i == 0 ? " x" : i == 1 ? " y" : " z");
}

// The force line with the limit in force at the end, and every limit a reload tightened.
template <int N>
void print_force_limits(const RunSummaryOf<N>& summary) {
  const SafetyConfigOf<N>& start = summary.limits_at_start;
  const SafetyConfigOf<N>& end = summary.limits_at_end;
  print_out("  max force        asked %.3f N, commanded %.3f N (limit %g N%s)\n", summary.max_abs_requested_N,
            summary.max_abs_output_N, end.max_force_N, N > 1 ? ", magnitudes" : "");
  std::string tightened;
  const auto note = [&](const std::string& name, double before, double after, const char* unit) {
    if (before == after) return;
    char item[160];
    std::snprintf(item, sizeof item, "%s%s %g -> %g %s", tightened.empty() ? "" : ", ", name.c_str(), before, after,
                  unit);
    tightened += item;
  };
  note("max force", start.max_force_N, end.max_force_N, "N");
  note("slew limit", start.slew_limit_N_per_s, end.slew_limit_N_per_s, "N/s");
  for (int i = 0; i < N; ++i) {
    note(axis_name("workspace min", N, i), component(start.workspace_min_m, i) * 1e3,
         component(end.workspace_min_m, i) * 1e3, "mm");
  }
  for (int i = 0; i < N; ++i) {
    note(axis_name("workspace max", N, i), component(start.workspace_max_m, i) * 1e3,
         component(end.workspace_max_m, i) * 1e3, "mm");
  }
  note("soft start", start.soft_start_s, end.soft_start_s, "s");
  note("soft-start threshold", start.soft_start_threshold_N, end.soft_start_threshold_N, "N");
  if (!tightened.empty()) print_out("  limits           tightened by a reload: %s\n", tightened.c_str());
}

// Each script of the scene running at the end: ok, or disabled with its fault once (the
// message says where in the script; t when, and with more than one axis the handle).
template <int N>
void print_scripts(const RunSummaryOf<N>& summary, const ScriptFaultPlaces<N>* places) {
  for (std::size_t i = 0; i < summary.scripts.size(); ++i) {
    const ScriptReport& script = summary.scripts[i];
    if (!script.disabled) {
      print_out("  script ok        %s\n", printable(script.name).c_str());
      continue;
    }
    std::string where;
    if constexpr (N > 1) {
      if (const auto* place = places != nullptr ? places->place(i) : nullptr) {
        char text[96];
        std::snprintf(text, sizeof text, ", x %.2f mm, y %.2f mm", place->x_m[0] * 1e3, place->x_m[1] * 1e3);
        where = text;
      }
    }
    print_out("  script disabled  %s (at t = %.3f s%s; 0 N for the remaining %llu ticks)\n",
              printable(script.fault).c_str(), script.fault_time_s, where.c_str(), count(script.skipped_calls));
  }
}

// Real time: the wake-up lateness, its bands, the scheduling obtained and overruns.
template <int N>
void print_timing(const RunSettings& settings, const RunSummaryOf<N>& summary) {
  print_out("  wake-up jitter   p50 %.2f us  p99 %.2f us  max %.2f us\n", us(summary.wake_late_ns.percentile_ns(0.50)),
            us(summary.wake_late_ns.percentile_ns(0.99)), us(summary.wake_late_ns.max_ns()));
  // The jitter histogram: ticks per band of lateness.
  const LatencyHistogram& late = summary.wake_late_ns;
  const std::uint64_t edges_ns[] = {10'000, 50'000, 100'000, 500'000, 1'000'000};
  std::uint64_t below = 0;
  std::string bands;
  const char* names[] = {"<10us", "10-50us", "50-100us", "100-500us", "0.5-1ms"};
  for (std::size_t b = 0; b < 5; ++b) {
    const std::uint64_t upto = late.count_at_most(edges_ns[b]);
    bands += std::string(b ? "  " : "") + names[b] + " " + std::to_string(upto - below);
    below = upto;
  }
  bands += "  >1ms " + std::to_string(late.count() - below);
  print_out("  jitter bands     %s\n", bands.c_str());
  print_out("  scheduling       %s\n", summary.realtime_note.c_str());
  if (!summary.realtime_hint.empty()) print_out("  to allow it      %s\n", summary.realtime_hint.c_str());
  // What deadline misses past the limits do, and why (--overruns, or the device).
  const bool chosen = settings.options.overruns != OverrunResponse::by_device;
  const char* why = chosen ? (summary.overruns_stop ? " (--overruns stop)" : " (--overruns report)")
                    : summary.overruns_stop
                        ? " (a late command leaves a motor pushing)"
                        : " (a simulated device: its world waits for the loop; --overruns stop rehearses a motor's)";
  print_out("  on overruns      %s%s\n", summary.overruns_stop ? "stop with zero force" : "report and run on", why);
  if (summary.overrun_warnings > 0 || summary.overrun_fault_kind != OverrunFault::none) {  // (a window crossing may come without a warning)
    // (The simulation's share only where there was one: a simulated plant's.)
    const std::string simulation =
        summary.simulation_misses > 0 ? ", " + std::to_string(summary.simulation_misses) +
                                            " while the simulated device computed (slower than real time)"
                                      : "";
    print_out("  overruns         %llu warnings (first at %.3f s), longest streak %u misses, "
              "at most %u misses in %u deadlines, %llu misses after late wake-ups (stalls of the system)%s\n",
              count(summary.overrun_warnings), summary.first_overrun_warning_s, summary.longest_miss_streak,
              summary.most_misses_in_window, summary.overrun_limits.window_deadlines, count(summary.stall_misses),
              simulation.c_str());
  }
  // Which limit was passed, and what it did.
  const char* label = summary.overrun_fault ? "FAULT           " : "past the limit  ";
  const char* outcome = summary.overrun_fault ? "zero force commanded, run stopped"
                                              : "reported only, the run went on";
  if (summary.overrun_fault_kind == OverrunFault::streak) {
    print_out("  %s sustained overrun at %.3f s (%u deadline misses in a row): %s\n", label,
              summary.overrun_fault_s, summary.overrun_limits.fault_ticks, outcome);
  } else if (summary.overrun_fault_kind == OverrunFault::window) {
    print_out("  %s frequent overruns at %.3f s (%u deadline misses within the last %u deadlines, more than %u): %s\n",
              label, summary.overrun_fault_s, summary.most_misses_in_window, summary.overrun_limits.window_deadlines,
              summary.overrun_limits.window_misses, outcome);
  }
}

}  // namespace

template <int N>
void print_run_summary(const SceneOf<N>& scene, const RunSettings& settings, std::string_view hand,
                       const RunSummaryOf<N>& summary, const ScriptFaultPlaces<N>* places) {
  const bool real_time = settings.options.pacing == Pacing::real_time;
  // Names and paths from files and the command line are printed in printable form.
  print_out("%s (%s) on %s:%s, %g Hz, %s, hand %s\n", scene.name.c_str(), printable(scene.source_path).c_str(),
            printable(settings.device).c_str(), printable(scene.device.name).c_str(), scene.rate_hz,
            real_time ? "real time" : "simulated time", std::string(hand).c_str());
  print_out("  ticks            %llu in %.3f s of device time, loop rate %.1f Hz\n", count(summary.ticks),
            summary.device_time_s, summary.achieved_rate_hz);
  print_force_limits(summary);
  const SafetyCounters& safety = summary.safety;
  print_out("  time clamped     %.3f s (%llu ticks); slew-limited %llu, soft start %llu, "
            "outside workspace %llu ticks\n",
            static_cast<double>(safety.clamped_ticks) * scene.period_s, count(safety.clamped_ticks),
            count(safety.slew_limited_ticks), count(safety.soft_start_ticks), count(safety.outside_workspace_ticks));
  if constexpr (N > 1) {
    print_out("  linkage          %llu ticks near a singular pose or unreachable (force held), "
              "%llu with a saturated motor (both scaled)\n",
              count(safety.pose_hold_ticks), count(safety.motor_saturated_ticks));
  }
  print_out("  faults           %llu non-finite forces\n", count(safety.nonfinite_faults));
  print_scripts(summary, places);
  std::string misses = "n/a (simulated time)";
  if (real_time) {
    misses = std::to_string(summary.deadline_misses);
    // Per minute of run, for runs long enough that the rate means something.
    if (summary.wall_time_s >= 1.0) {
      char rate[48];
      std::snprintf(rate, sizeof rate, " (%.1f per minute)", 60.0 * static_cast<double>(summary.deadline_misses) / summary.wall_time_s);
      misses += rate;
    }
  }
  print_out("  deadline misses  %s\n", misses.c_str());
  print_out("  tick compute     p50 %.2f us  p99 %.2f us  max %.2f us\n", us(summary.compute_ns.percentile_ns(0.50)),
            us(summary.compute_ns.percentile_ns(0.99)), us(summary.compute_ns.max_ns()));
  if (real_time) print_timing(settings, summary);
  flush_out();
}

// The axis counts scenes are compiled for.
#define HAPSCENE_PRINT_RUN_SUMMARY(N)                                                                      \
  template void print_run_summary<N>(const SceneOf<N>&, const RunSettings&, std::string_view, const RunSummaryOf<N>&, \
                                     const ScriptFaultPlaces<N>*);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_PRINT_RUN_SUMMARY)
#undef HAPSCENE_PRINT_RUN_SUMMARY

}  // namespace hapscene
