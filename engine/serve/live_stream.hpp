#pragma once
// The live view's stream (GET /api/stream): the tap the loop pushes into, the pump that
// drains it kLiveEventsPerSecond times a second into one event for every client, the
// clients' bounded queues, the page's log and the run's script faults. Nothing here is
// waited for by the loop: it sees only the tap.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/run/loop_monitor.hpp"
#include "engine/scene/scene.hpp"
#include "engine/serve/live_events.hpp"
#include "engine/serve/live_view.hpp"
#include "engine/serve/stream_tap.hpp"

namespace httplib {
struct Response;
}

namespace hapscene {

// A client of /api/stream: its events waiting to be written, and what it missed.
struct LiveStreamClient {
  std::deque<std::string> queue;
  std::uint64_t dropped{};
  bool closed{};
};

template <int N>
class LiveStreamOf {
 public:
  // `stopping` is the view's: set, the pump ends and the clients' writers finish.
  LiveStreamOf(const SceneOf<N>& scene, const std::atomic<bool>& stopping);
  LiveStreamOf(const LiveStreamOf&) = delete;
  LiveStreamOf& operator=(const LiveStreamOf&) = delete;

  StreamTapOf<N>& tap() noexcept { return tap_; }
  // Starts the pump; `monitor` may be null, `link_names` are the device's boards.
  void start(LoopMonitor* monitor, std::vector<std::string> link_names);
  // GET /api/stream on a handler's thread (503 beyond the gate's streams).
  void serve(httplib::Response& res);
  // A line for the page's log, sent with the next event. Any thread.
  void add_log(const std::string& line);
  // The run's script faults so far (the last kLiveClientQueue).
  std::vector<nlohmann::json> fault_history();

  // Before `stopping` is set: waits for the run's last event when the run is over (the
  // pump sends it within two periods), then for the clients' writers to take what is
  // queued; at most 400 ms.
  void drain();
  // After `stopping` is set: wakes the writers, ends the pump, and waits up to 300 ms for
  // the streams to end their responses.
  void stop();

  std::uint64_t dropped_events();
  std::uint64_t events_sent() const noexcept { return seq_.load(); }

 private:
  void pump();
  // Every sample, fault and link counter since the last event, as the event (without
  // its log); `any`: samples came.
  nlohmann::json collect(bool* any);
  // The event to every client, with the pending log and each client's count of dropped
  // events; after the run's last sample, the "end" event too.
  void deliver(nlohmann::json event, bool any);

  StreamTapOf<N> tap_;
  double period_s_{};
  const std::atomic<bool>& stopping_;
  LoopMonitor* monitor_{};
  std::vector<std::string> link_names_;

  std::mutex clients_mutex_;  // clients_, their queues, pending_log_, log_history_, fault_history_
  std::condition_variable clients_cv_;
  std::vector<std::shared_ptr<LiveStreamClient>> clients_;
  std::vector<std::string> pending_log_;
  std::deque<std::string> log_history_;  // the last kLiveLogHistory lines sent, for new clients
  std::vector<nlohmann::json> fault_history_;
  std::uint64_t dropped_events_total_{};

  // The pump thread's own.
  DeviceLinkHealth health_{};
  LinkEventMemory link_memory_{};
  StreamSampleOf<N> previous_{};
  bool have_previous_{};
  double energy_J_{};
  bool overrun_logged_{false};  // a passed overrun limit went to the log
  std::atomic<std::uint64_t> seq_{0};
  std::atomic<bool> ended_{false};  // the "end" event was queued
  std::thread pump_thread_;
};

}  // namespace hapscene
