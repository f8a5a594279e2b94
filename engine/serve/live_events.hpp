#pragma once
// What the stream's events say besides the samples (docs/reference/live-view-api.md): how
// a run ended, the loop's timing, the safety counters, a script fault, and each board
// link's counters. Plain JSON writers, on the pump's thread.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/devices/link_health.hpp"
#include "engine/run/loop_monitor.hpp"
#include "engine/scene/safety.hpp"
#include "engine/serve/stream_tap.hpp"

namespace hapscene {

// The first overrun limit passed, in the terminal's words ("" when none was).
std::string overrun_text(const LoopMonitor& monitor);

// The "end" event's data: how the run ended, and for a stop on overruns or a lost device
// the terminal's words ({"reason", "fault", "message"}).
nlohmann::json run_end_json(const LoopMonitor& monitor);

// status.safety: the safety stage's counters.
nlohmann::json safety_counters_json(const SafetyCounters& safety);

// status's deadline_misses, overrun_warnings, wake_late_max_us and compute_max_us (null
// without a monitor); takes the maxima since the last event.
void add_loop_timing(nlohmann::json& status, LoopMonitor* monitor);

// One script fault as an event's "script_faults" entry.
nlohmann::json script_fault_json(const StreamScriptFault& fault);

// What status.links remembers between events: the counters of the event before, and
// each link's last round-trip mean.
struct LinkEventMemory {
  DeviceLinkHealth before{};
  nlohmann::json last_mean_us[kMaxDeviceLinks]{};
};

// status.links: one object per board, the round trip's mean over the replies since the
// previous event (`fresh`: new counters came; without replies the mean is null then, and
// the last mean otherwise).
nlohmann::json links_json(const DeviceLinkHealth& health, bool fresh, const std::vector<std::string>& link_names,
                          LinkEventMemory& memory);

}  // namespace hapscene
