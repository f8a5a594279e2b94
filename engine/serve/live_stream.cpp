#include "engine/serve/live_stream.hpp"

#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/serve/connection_gate.hpp"
#include "engine/serve/live_requests.hpp"
#include "engine/serve/version_description.hpp"

namespace hapscene {

using json = nlohmann::json;

namespace {

using StreamClock = std::chrono::steady_clock;

// The ring between the loop and the pump: 16384 samples (16 s at 1 kHz); the pump empties
// it 50 times a second.
constexpr std::size_t kTapCapacity = 1u << 14;

// An event's name of an axis's column: "x_m", "force_N", "output_N" for one axis; "x_m",
// "y_m", "force_x_N", "output_y_N"... for more.
std::string axis_key(int axes, const char* quantity, int i, const char* unit) {
  const std::string axis = kAxisNames[i];
  if (quantity[0] == '\0') return axis + unit;
  return std::string(quantity) + (axes == 1 ? "" : "_" + axis) + unit;
}

}  // namespace

std::uint64_t live_stride(double rate_hz) {
  return static_cast<std::uint64_t>(std::max(1.0, std::ceil(rate_hz / kLiveMaxTicksPerSecond)));
}

template <int N>
LiveStreamOf<N>::LiveStreamOf(const SceneOf<N>& scene, const std::atomic<bool>& stopping)
    : tap_(kTapCapacity, live_stride(scene.rate_hz), scene.rate_hz), period_s_(scene.period_s), stopping_(stopping) {}

template <int N>
void LiveStreamOf<N>::start(LoopMonitor* monitor, std::vector<std::string> link_names) {
  monitor_ = monitor;
  link_names_ = std::move(link_names);
  pump_thread_ = std::thread([this] { pump(); });
}

template <int N>
void LiveStreamOf<N>::serve(httplib::Response& res) {
  // Streams have threads of their own, as many as the gate allows.
  if (!GatedServer::become_stream()) {
    error_response(res, 503, "too many streams open (at most " + std::to_string(ConnectionLimits{}.streams_total) +
                                 ", " + std::to_string(ConnectionLimits{}.streams_per_peer) + " per address)");
    return;
  }
  auto client = std::make_shared<LiveStreamClient>();
  {
    // The log so far first ("event: log", the last kLiveLogHistory lines): what happened
    // before the page opened. Lines not yet sent come in the client's next events.
    std::lock_guard lock(clients_mutex_);
    client->queue.push_back("event: log\ndata: " + json{{"log", log_history_}}.dump() + "\n\n");
    clients_.push_back(client);
  }
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Accel-Buffering", "no");
  res.set_chunked_content_provider(
      "text/event-stream",
      [this, client](std::size_t /*offset*/, httplib::DataSink& sink) {
        std::string out;
        {
          std::unique_lock lock(clients_mutex_);
          clients_cv_.wait_for(lock, std::chrono::milliseconds(500),
                               [&] { return !client->queue.empty() || stopping_.load(); });
          for (std::string& event : client->queue) out += event;
          client->queue.clear();
        }
        if (out.empty()) {
          if (stopping_.load() || ended_.load()) {  // the run is over and its last event out
            sink.done();
            return true;
          }
          out = ": keep-alive\n\n";
        }
        return sink.write(out.data(), out.size());
      },
      [this, client](bool /*success*/) {
        std::lock_guard lock(clients_mutex_);
        client->closed = true;
        std::erase(clients_, client);
      });
}

template <int N>
void LiveStreamOf<N>::add_log(const std::string& line) {
  std::lock_guard lock(clients_mutex_);
  if (pending_log_.size() < 1000) pending_log_.push_back(line);
}

template <int N>
std::vector<json> LiveStreamOf<N>::fault_history() {
  std::lock_guard lock(clients_mutex_);
  return fault_history_;
}

template <int N>
std::uint64_t LiveStreamOf<N>::dropped_events() {
  std::lock_guard lock(clients_mutex_);
  return dropped_events_total_;
}

template <int N>
void LiveStreamOf<N>::drain() {
  for (int i = 0; i < 20 && tap_.finished() && !ended_.load() && pump_thread_.joinable(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  for (int i = 0; i < 20 && pump_thread_.joinable(); ++i) {
    bool empty = true;
    {
      std::lock_guard lock(clients_mutex_);
      for (const auto& client : clients_) empty = empty && client->queue.empty();
    }
    if (empty) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

template <int N>
void LiveStreamOf<N>::stop() {
  clients_cv_.notify_all();
  if (pump_thread_.joinable()) pump_thread_.join();
  for (int i = 0; i < 30; ++i) {
    {
      std::lock_guard lock(clients_mutex_);
      if (clients_.empty()) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

template <int N>
json LiveStreamOf<N>::collect(bool* any) {
  // Every sample since the last event, column by column.
  json t_s = json::array();
  json x[N], f[N], o[N];
  for (int i = 0; i < N; ++i) x[i] = f[i] = o[i] = json::array();
  json first_tick = nullptr;
  StreamSampleOf<N> sample;
  *any = false;
  while (tap_.pop(&sample)) {
    if (!*any) first_tick = sample.tick;
    *any = true;
    t_s.push_back(sample.t_s);
    for (int i = 0; i < N; ++i) {
      x[i].push_back(component(sample.x_m, i));
      f[i].push_back(component(sample.force_N, i));
      o[i].push_back(component(sample.output_N, i));
    }
    // The passivity observer: the work the handle's motion did against the commanded force.
    if (have_previous_) {
      for (int i = 0; i < N; ++i) {
        energy_J_ -= component(previous_.output_N, i) * (component(sample.x_m, i) - component(previous_.x_m, i));
      }
    }
    previous_ = sample;
    have_previous_ = true;
  }
  json event{{"seq", seq_.load()}, {"tick", first_tick}, {"stride", tap_.stride()}, {"t_s", t_s}};
  for (int i = 0; i < N; ++i) {
    event[axis_key(N, "", i, "_m")] = x[i];
    event[axis_key(N, "force", i, "_N")] = f[i];
    event[axis_key(N, "output", i, "_N")] = o[i];
  }
  if constexpr (N > 1) {
    json proxies = json::array();
    for (std::size_t i = 0; i < previous_.proxy_count; ++i) proxies.push_back(axes_json(previous_.proxies_m[i]));
    event["proxies_m"] = proxies;
  }
  // Script faults, each once, as the tap copied them.
  json new_faults = json::array();
  StreamScriptFault fault;
  while (tap_.pop_fault(&fault)) new_faults.push_back(script_fault_json(fault));
  // The device's links: the newest counters the tap took.
  bool health_fresh = false;
  while (tap_.pop_link_health(&health_)) health_fresh = true;
  event["script_faults"] = new_faults;

  const std::uint64_t ticks = tap_.ticks();
  json status{{"ticks", ticks},
              {"t_s", static_cast<double>(ticks) * period_s_},
              {"energy_J", energy_J_},
              {"dropped_ticks", tap_.dropped()},
              {"finished", tap_.finished()},
              {"safety", safety_counters_json(previous_.safety)}};
  add_loop_timing(status, monitor_);
  json disabled = json::array();
  for (int i = 0; i < 64; ++i) {
    if ((previous_.scripts_disabled >> i) & 1u) disabled.push_back(i);
  }
  status["scripts_disabled"] = disabled;
  status["script_faults"] = tap_.faults_seen();
  status["links"] = links_json(health_, health_fresh, link_names_, link_memory_);
  event["status"] = status;
  return event;
}

template <int N>
void LiveStreamOf<N>::deliver(json event, bool any) {
  std::lock_guard lock(clients_mutex_);
  if (ended_.load()) return;  // after the run's last event ("event: end") nothing more is sent
  // An overrun limit passed that did not stop the run (a simulated device): said once.
  if (monitor_ != nullptr && monitor_->overrun_kind() != OverrunFault::none && !overrun_logged_) {
    overrun_logged_ = true;
    if (!monitor_->overrun_stopped()) pending_log_.push_back(overrun_text(*monitor_));
  }
  event["log"] = json(pending_log_);
  for (std::string& line : pending_log_) {
    if (log_history_.size() >= kLiveLogHistory) log_history_.pop_front();
    log_history_.push_back(std::move(line));
  }
  pending_log_.clear();
  for (const json& new_fault : event["script_faults"]) {
    if (fault_history_.size() >= kLiveClientQueue) fault_history_.erase(fault_history_.begin());
    fault_history_.push_back(new_fault);
  }
  std::string body = event.dump();
  body.pop_back();  // the closing brace: each client's count follows
  const bool finishing = tap_.finished() && !any && !ended_;
  // How the run ended, with the terminal's words for a fault (docs/reference/live-view-api.md).
  const std::string end_data = finishing && monitor_ != nullptr ? run_end_json(*monitor_).dump() : "{}";
  for (const auto& client : clients_) {
    if (client->queue.size() >= kLiveClientQueue) {
      client->queue.pop_front();
      ++client->dropped;
      ++dropped_events_total_;
    }
    std::string event_text = "id: " + std::to_string(seq_.load()) + "\ndata: " + body + ",\"dropped_events\":" +
                             std::to_string(client->dropped) + "}\n\n";
    if (finishing) event_text += "event: end\ndata: " + end_data + "\n\n";
    client->queue.push_back(std::move(event_text));
  }
  if (finishing) ended_.store(true);
  ++seq_;
  clients_cv_.notify_all();
}

// Drains the tap kLiveEventsPerSecond times a second, with the loop's rate measured
// between events.
template <int N>
void LiveStreamOf<N>::pump() {
  const auto interval = std::chrono::duration_cast<StreamClock::duration>(std::chrono::duration<double>(1.0 / kLiveEventsPerSecond));
  auto next = StreamClock::now() + interval;
  auto last_time = StreamClock::now();
  std::uint64_t last_ticks = 0;
  double rate_hz = 0.0;
  while (!stopping_.load()) {
    std::this_thread::sleep_until(next);
    next += interval;
    bool any = false;
    json event = collect(&any);
    const auto now = StreamClock::now();
    const std::uint64_t ticks = event["status"]["ticks"].get<std::uint64_t>();
    const double dt_s = std::chrono::duration<double>(now - last_time).count();
    if (dt_s > 0.0) {
      const double instant_hz = static_cast<double>(ticks - last_ticks) / dt_s;
      rate_hz = rate_hz == 0.0 ? instant_hz : 0.8 * rate_hz + 0.2 * instant_hz;
    }
    last_ticks = ticks;
    last_time = now;
    event["status"]["loop_rate_hz"] = rate_hz;
    deliver(std::move(event), any);
  }
}

#define HAPSCENE_LIVE_STREAM(N) template class LiveStreamOf<N>;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_LIVE_STREAM)
#undef HAPSCENE_LIVE_STREAM

}  // namespace hapscene
