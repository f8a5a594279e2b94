#include "engine/serve/live_events.hpp"

#include <algorithm>
#include <cstdio>

namespace hapscene {

using json = nlohmann::json;

std::string overrun_text(const LoopMonitor& monitor) {
  if (monitor.overrun_kind() == OverrunFault::none) return {};
  const bool streak = monitor.overrun_kind() == OverrunFault::streak;
  char text[256];
  std::snprintf(text, sizeof text, "%s at %.3f s (%s): %s", streak ? "sustained overrun" : "frequent overruns",
                monitor.overrun_t_s(),
                streak ? "deadline misses in a row, made by the loop's own work"
                       : "too many deadline misses within the window",
                monitor.overrun_stopped()
                    ? "zero force commanded, run stopped"
                    : "reported only, the run went on (a simulated device's world waits for the loop)");
  return text;
}

json run_end_json(const LoopMonitor& monitor) {
  const std::string overrun = overrun_text(monitor);
  switch (monitor.end()) {
    case RunEnd::running: return {{"reason", "running"}, {"fault", false}, {"message", overrun}};
    case RunEnd::duration: return {{"reason", "duration"}, {"fault", false}, {"message", "ran its whole duration"}};
    case RunEnd::stop_requested: return {{"reason", "stopped"}, {"fault", false}, {"message", "stopped on request"}};
    case RunEnd::overrun_fault: return {{"reason", "overrun_fault"}, {"fault", true}, {"message", "FAULT: " + overrun}};
    case RunEnd::device_lost:
      return {{"reason", "device_lost"}, {"fault", true},
              {"message", "FAULT: the device was lost: zero force, run stopped (the terminal's summary says why)"}};
  }
  return {{"reason", "running"}, {"fault", false}, {"message", overrun}};
}

json safety_counters_json(const SafetyCounters& safety) {
  return {{"clamped_ticks", safety.clamped_ticks},
          {"slew_limited_ticks", safety.slew_limited_ticks},
          {"soft_start_ticks", safety.soft_start_ticks},
          {"outside_workspace_ticks", safety.outside_workspace_ticks},
          {"nonfinite_faults", safety.nonfinite_faults},
          {"position_hold_ticks", safety.position_hold_ticks},
          {"pose_hold_ticks", safety.pose_hold_ticks},
          {"motor_saturated_ticks", safety.motor_saturated_ticks}};
}

void add_loop_timing(json& status, LoopMonitor* monitor) {
  if (monitor == nullptr) {
    status["deadline_misses"] = nullptr;
    status["overrun_warnings"] = nullptr;
    status["wake_late_max_us"] = nullptr;
    status["compute_max_us"] = nullptr;
    return;
  }
  status["deadline_misses"] = monitor->deadline_misses();
  status["overrun_warnings"] = monitor->overrun_warnings();
  status["wake_late_max_us"] = static_cast<double>(monitor->take_wake_late_max_ns()) * 1e-3;
  status["compute_max_us"] = static_cast<double>(monitor->take_compute_max_ns()) * 1e-3;
}

namespace {

// The stream's name of a script fault's kind.
const char* script_fault_kind_name(ScriptFault kind) {
  switch (kind) {
    case ScriptFault::none: return "none";
    case ScriptFault::error: return "error";
    case ScriptFault::bad_return: return "bad_return";
    case ScriptFault::instruction_budget: return "instruction_budget";
    case ScriptFault::time_limit: return "time_limit";
    case ScriptFault::memory_limit: return "memory_limit";
  }
  return "fault";
}

}  // namespace

json script_fault_json(const StreamScriptFault& fault) {
  return {{"number", fault.number},
          {"script", fault.script},
          {"t_s", fault.t_s},
          {"kind", script_fault_kind_name(fault.kind)},
          {"message", std::string(fault.message, fault.length)}};
}

json links_json(const DeviceLinkHealth& health, bool fresh, const std::vector<std::string>& link_names,
                LinkEventMemory& memory) {
  json out = json::array();
  for (std::size_t i = 0; i < health.links && i < kMaxDeviceLinks; ++i) {
    const LinkHealth& h = health.link[i];
    LinkHealth& before = memory.before.link[i];
    json rtt{{"replies", h.round_trip_count}, {"max", static_cast<double>(h.round_trip_max_ns) * 1e-3}};
    const std::uint64_t replies = h.round_trip_count - std::min(h.round_trip_count, before.round_trip_count);
    rtt["mean"] = replies > 0 ? json(static_cast<double>(h.round_trip_sum_ns - before.round_trip_sum_ns) * 1e-3 /
                                     static_cast<double>(replies))
                              : (fresh ? json(nullptr) : memory.last_mean_us[i]);
    if (replies > 0) memory.last_mean_us[i] = rtt["mean"];
    json link{{"board", i < link_names.size() ? json(link_names[i]) : json(nullptr)},
              {"joint", health.links > 1 ? json(i + 1) : json(nullptr)},
              {"protocol", h.protocol},
              {"state", h.state},
              {"commands", h.commands},
              {"replies", h.replies},
              {"crc_errors", h.crc_errors},
              {"length_errors", h.length_errors},
              {"bytes_skipped", h.bytes_skipped},
              {"lost_frames", h.lost_frames},
              {"unanswered", h.unanswered},
              {"frames_not_sent", h.frames_not_sent},
              {"stale_reads", h.stale_reads},
              {"board_timeouts", h.board_timeouts},
              {"implausible", h.implausible},
              {"resyncs", h.resyncs},
              {"connects", h.connects},
              {"board_resets", h.board_resets},
              {"silences", h.silences},
              {"vanished", h.vanished},
              {"round_trip_us", rtt}};
    link["board_saw"] = h.board_stats ? json{{"frames", h.board_frames},
                                              {"crc_errors", h.board_crc_errors},
                                              {"length_errors", h.board_length_errors},
                                              {"bytes_skipped", h.board_bytes_skipped},
                                              {"lost_frames", h.board_lost_frames},
                                              {"command_timeouts", h.board_command_timeouts}}
                                      : json(nullptr);
    out.push_back(link);
    before = h;
  }
  return out;
}

}  // namespace hapscene
