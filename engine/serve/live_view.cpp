#include "engine/serve/live_view.hpp"

#include <httplib.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <functional>
#include <optional>
#include <mutex>
#include <random>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/file_replace.hpp"
#include "engine/base/json_source.hpp"
#include "engine/harness/validate_kind.hpp"
#include "engine/load/environment.hpp"
#include "engine/serve/connection_gate.hpp"
#include "engine/serve/live_job.hpp"
#include "engine/serve/live_requests.hpp"
#include "engine/serve/parameters.hpp"
#include "engine/serve/stream_tap.hpp"
#include "engine/serve/ui_assets.hpp"
#include "engine/serve/version_description.hpp"

namespace hapscene {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// The ring between the loop and the pump: 16384 samples (16 s at 1 kHz); the pump empties
// it 50 times a second.
constexpr std::size_t kTapCapacity = 1u << 14;
// The first overrun limit passed, in the terminal's words ("" when none was).
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

// The "end" event's data: how the run ended, and for a stop on overruns or a lost device
// the terminal's words ({"reason", "fault", "message"}).
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

std::filesystem::file_time_type stamp_of(const std::string& path) {
  std::error_code error;
  const auto stamp = std::filesystem::last_write_time(path, error);
  return error ? std::filesystem::file_time_type{} : stamp;
}

}  // namespace

// A client of /api/stream: its events waiting to be written, and what it missed. Not in
// the anonymous namespace: LiveViewOf<N>::Impl, which has external linkage, holds them.
struct LiveStreamClient {
  std::deque<std::string> queue;
  std::uint64_t dropped{};
  bool closed{};
};

std::uint64_t live_stride(double rate_hz) {
  return static_cast<std::uint64_t>(std::max(1.0, std::ceil(rate_hz / kLiveMaxTicksPerSecond)));
}

template <int N>
struct LiveViewOf<N>::Impl {
  using Scene = SceneOf<N>;

  Impl(const UiAddress& where, std::string environment_path, const Scene& scene)
      : address(where),
        path(std::move(environment_path)),
        tap(kTapCapacity, live_stride(scene.rate_hz), scene.rate_hz),
        period_s(scene.period_s) {
    base_dir = std::filesystem::path(path).parent_path().string();
    if (base_dir.empty()) base_dir = ".";
    text = environment_text_of(path);
    file_text = text;
    file_stamp = stamp_of(path);
    take(describe_version<N>(scene, text, path, tap.stride()));
    token = new_token();
    server.set_payload_max_length(kMaxRequestBodyBytes);
    bound_port = address.port == 0 ? server.bind_to_any_port(address.host) : (server.bind_to_port(address.host, address.port) ? address.port : -1);
    if (bound_port < 0) {
      throw InputError("--ui " + address.host + ":" + std::to_string(address.port) + ": cannot listen there (" +
                       std::string(std::strerror(errno)) + ")");
    }
  }

  void take(VersionDescription description) {
    parameters = std::move(description.parameters);
    scene_json = std::move(description.scene_json);
  }

  // Loads and describes `candidate` on a job's thread (nullopt: the view stopped first).
  // Throws what the loader throws.
  std::optional<PreparedVersion<N>> prepare(const std::string& candidate) {
    return run_job<PreparedVersion<N>>(
        [candidate, file = path, dir = base_dir, stride = tap.stride()] {
          PreparedVersion<N> out;
          out.loaded = load_version<N>(candidate, file, dir);
          out.description = describe_version<N>(out.loaded->scene, candidate, file, stride);
          return out;
        },
        stopping);
  }

  // The file changed on disk since it was last read or written (an editor saved it; the
  // watcher reloads it), or the watcher took a new version from the files (a script's
  // defaults edited): the file's text becomes the current values, described as the loop
  // now runs them. With doc_mutex held; every endpoint calls it first.
  void refresh_from_file() {
    const auto stamp = stamp_of(path);
    const std::uint64_t versions = watcher != nullptr ? watcher->file_versions() : 0;
    if (stamp == file_stamp && versions == seen_file_versions) return;
    file_stamp = stamp;
    seen_file_versions = versions;
    try {
      const std::string fresh = environment_text_of(path);
      std::optional<PreparedVersion<N>> prepared = prepare(fresh);
      if (!prepared) return;
      take(std::move(prepared->description));
      text = fresh;
      file_text = fresh;
    } catch (const std::exception&) {
      // A broken file: the running version (and these values) keep going, as a reload does.
    }
  }

  json scene_with_state() {
    json out = scene_json;
    out["unsaved"] = text != file_text;
    out["device"]["links"] = link_names;
    out["device"]["hand_pointer"] = pointer != nullptr;  // POST /api/hand takes the simulated hand
    std::lock_guard lock(clients_mutex);
    out["script_faults"] = fault_history;
    return out;
  }

  // POST /api/hand: on a simulated device, the pointer takes the hand toward a point of the
  // workspace ({"x_m": X}, and "y_m" on a 2-DOF device), or lets it go ({"release": true}).
  void hand(const std::string& request_body, httplib::Response& res) {
    if (pointer == nullptr) {
      error_response(res, 409, "this device's hand is not the page's to move (only --device sim's is): on a real device it is yours");
      return;
    }
    std::string form = "{\"x_m\": X";
    for (int i = 1; i < N; ++i) form += std::string(", \"") + kAxisNames[i] + "_m\": " + static_cast<char>(std::toupper(kAxisNames[i][0]));
    form += "} or {\"release\": true}";
    json body;
    try {
      body = json::parse(request_body);
    } catch (const json::exception&) {
      error_response(res, 400, "request: expected a JSON object " + form);
      return;
    }
    if (!body.is_object()) {
      error_response(res, 400, "request: expected a JSON object " + form);
      return;
    }
    if (body.contains("release")) {
      if (body.size() != 1 || body["release"] != true) {
        error_response(res, 400, "request: expected {\"release\": true} alone");
        return;
      }
      pointer->release();
      res.set_content(json{{"hand", "released"}}.dump(), "application/json");
      return;
    }
    if (body.size() != static_cast<std::size_t>(N)) {
      error_response(res, 400, "request: expected a JSON object " + form);
      return;
    }
    // The workspace of the version running, as GET /api/scene gives it to the page.
    Axes<N> workspace_min_m{};
    Axes<N> workspace_max_m{};
    {
      std::lock_guard lock(doc_mutex);
      const json& device = scene_json["device"];
      if constexpr (N == 1) {
        workspace_min_m = device["workspace_min_m"].get<double>();
        workspace_max_m = device["workspace_max_m"].get<double>();
      } else {
        for (int i = 0; i < N; ++i) {
          workspace_min_m[i] = device["workspace_min_m"][static_cast<std::size_t>(i)].get<double>();
          workspace_max_m[i] = device["workspace_max_m"][static_cast<std::size_t>(i)].get<double>();
        }
      }
    }
    Axes<N> x_m{};
    json shown = json::object();
    for (int i = 0; i < N; ++i) {
      const std::string key = std::string(kAxisNames[i]) + "_m";
      const auto found = body.find(key);
      if (found == body.end() || !found->is_number() || !std::isfinite(found->get<double>())) {
        error_response(res, 400, "request: \"" + key + "\" must be a finite number of metres (" + form + ")");
        return;
      }
      const double value_m = found->get<double>();
      const double low_m = component(workspace_min_m, i);
      const double high_m = component(workspace_max_m, i);  // the running version's (what the page shows)
      if (value_m < low_m || value_m > high_m) {
        error_response(res, 400, key + ": " + format_number(value_m) + " m is outside the workspace [" +
                                     format_number(low_m) + ", " + format_number(high_m) + "] m");
        return;
      }
      if constexpr (N == 1) {
        x_m = value_m;
      } else {
        x_m[i] = value_m;
      }
      shown[key] = value_m;
    }
    pointer->take(x_m);
    shown["hand"] = "pointer";
    res.set_content(shown.dump(), "application/json");
  }

  // POST /api/params.
  void change(const std::string& request_body, httplib::Response& res) {
    json body;
    try {
      body = json::parse(request_body);
    } catch (const json::exception&) {
      error_response(res, 400, "request: expected a JSON object {\"effect\": I, \"parameter\": NAME, \"value\": V}");
      return;
    }
    if (!body.is_object() || !body.contains("effect") || !body["effect"].is_number_unsigned() ||
        !body.contains("parameter") || !body["parameter"].is_string() || !body.contains("value")) {
      error_response(res, 400, "request: expected a JSON object {\"effect\": I, \"parameter\": NAME, \"value\": V}");
      return;
    }
    std::lock_guard lock(doc_mutex);
    refresh_from_file();
    try {
      const std::string candidate = with_parameter(text, parameters, body["effect"].get<std::size_t>(),
                                                   body["parameter"].get<std::string>(), body["value"]);
      std::optional<PreparedVersion<N>> prepared = prepare(candidate);
      if (!prepared) {
        error_response(res, 503, "the run is ending");
        return;
      }
      // Described before it is handed over (the loop owns it from then on).
      const std::string refusal = watcher->offer_version(std::move(prepared->loaded));
      if (!refusal.empty()) {
        error_response(res, 400, refusal);
        return;
      }
      take(std::move(prepared->description));
      text = candidate;
      ++changes;
      res.set_content(scene_with_state().dump(), "application/json");
    } catch (const InputError& error) {
      error_response(res, 400, error.what());
    } catch (const std::exception& error) {
      error_response(res, 400, error.what());
    }
  }

  // POST /api/save: the current values into the file, replacing it whole
  // (engine/base/file_replace.hpp: never through a link planted next to it), through the
  // watcher so that it does not reload what it wrote.
  void save(httplib::Response& res) {
    std::lock_guard lock(doc_mutex);
    refresh_from_file();
    if (std::filesystem::path(path).extension() == ".lua") {
      error_response(res, 409,
                     path + ": a script run as an environment of its own has no environment file to save values "
                            "into (its changed values last for this run); to keep them, run an environment file "
                            "that names the script and gives them as \"params\" (hapscene new script NAME)");
      return;
    }
    const std::string problem = watcher->write_watched([&]() -> std::string {
      const FileWriteOutcome outcome = replace_file(path, text, SpecialPath::refuse);
      if (outcome.ok()) return {};
      const std::string reason = std::strerror(outcome.error_number);
      if (outcome.failed == FileWriteStep::open) return path + ": cannot write a new file next to it (" + reason + ")";
      return path + ": cannot replace the file (" + reason + ")";
    });
    if (!problem.empty()) {
      error_response(res, 500, problem);
      return;
    }
    file_text = text;
    file_stamp = stamp_of(path);
    res.set_content(json{{"saved", path}, {"bytes", text.size()}}.dump(), "application/json");
  }

  // POST /api/validate: the harness on the current values, on a job's thread at a lower
  // priority than the run (off the loop; one at a time).
  void validate(httplib::Response& res) {
    std::unique_lock busy(validate_mutex, std::try_to_lock);
    if (!busy.owns_lock()) {
      error_response(res, 409, "a validate run is already running");
      return;
    }
    std::string version;
    {
      std::lock_guard lock(doc_mutex);
      refresh_from_file();  // the version the loop runs, after any reload
      version = text;
    }
    try {
      std::optional<json> out = run_job<json>(
          [version, file = path, dir = base_dir] {
            setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
            const EnvironmentOf<N> environment = compile_environment_of<N>(version, file, dir);
            const ValidationReportOf<N> report = validate_environment(environment, {}, HarnessOptions{});
            return json{{"pass", report.pass}, {"table", format_report_table(report)}, {"report", report_to_json(report)}};
          },
          stopping);
      if (!out) {
        error_response(res, 503, "the run is ending");
        return;
      }
      res.set_content(out->dump(), "application/json");
    } catch (const std::exception& error) {
      error_response(res, 400, error.what());
    }
  }

  // GET /api/stream: the client's events as they come; a keep-alive comment when none.
  void stream(httplib::Response& res) {
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
      std::lock_guard lock(clients_mutex);
      client->queue.push_back("event: log\ndata: " + json{{"log", log_history}}.dump() + "\n\n");
      clients.push_back(client);
    }
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Accel-Buffering", "no");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, client](std::size_t /*offset*/, httplib::DataSink& sink) {
          std::string out;
          {
            std::unique_lock lock(clients_mutex);
            clients_cv.wait_for(lock, std::chrono::milliseconds(500),
                                [&] { return !client->queue.empty() || stopping.load(); });
            for (std::string& event : client->queue) out += event;
            client->queue.clear();
          }
          if (out.empty()) {
            if (stopping.load() || ended.load()) {  // the run is over and its last event out
              sink.done();
              return true;
            }
            out = ": keep-alive\n\n";
          }
          return sink.write(out.data(), out.size());
        },
        [this, client](bool /*success*/) {
          std::lock_guard lock(clients_mutex);
          client->closed = true;
          std::erase(clients, client);
        });
  }

  static json fault_json(const StreamScriptFault& f) {
    return {{"number", f.number},
            {"script", f.script},
            {"t_s", f.t_s},
            {"kind", script_fault_kind_name(f.kind)},
            {"message", std::string(f.message, f.length)}};
  }

  // The links' counters for status.links (the pump's): one object per board, the round
  // trip's mean over the replies since the previous event (fresh: new counters came).
  json links_json(bool fresh) {
    json out = json::array();
    for (std::size_t i = 0; i < health.links && i < kMaxDeviceLinks; ++i) {
      const LinkHealth& h = health.link[i];
      LinkHealth& before = health_before.link[i];
      json rtt{{"replies", h.round_trip_count}, {"max", static_cast<double>(h.round_trip_max_ns) * 1e-3}};
      const std::uint64_t replies = h.round_trip_count - std::min(h.round_trip_count, before.round_trip_count);
      rtt["mean"] = replies > 0 ? json(static_cast<double>(h.round_trip_sum_ns - before.round_trip_sum_ns) * 1e-3 /
                                       static_cast<double>(replies))
                                : (fresh ? json(nullptr) : last_mean_us[i]);
      if (replies > 0) last_mean_us[i] = rtt["mean"];
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

  // The pump: drains the tap kLiveEventsPerSecond times a second into one event for
  // every client.
  void pump() {
    const auto interval = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / kLiveEventsPerSecond));
    auto next = Clock::now() + interval;
    auto last_time = Clock::now();
    std::uint64_t last_ticks = 0;
    double rate_hz = 0.0;
    StreamSampleOf<N> sample;
    while (!stopping.load()) {
      std::this_thread::sleep_until(next);
      next += interval;
      // Every sample since the last event, column by column.
      json t_s = json::array();
      json x[N], f[N], o[N];
      for (int i = 0; i < N; ++i) x[i] = f[i] = o[i] = json::array();
      json first_tick = nullptr;
      bool any = false;
      while (tap.pop(&sample)) {
        if (!any) first_tick = sample.tick;
        any = true;
        t_s.push_back(sample.t_s);
        for (int i = 0; i < N; ++i) {
          x[i].push_back(component(sample.x_m, i));
          f[i].push_back(component(sample.force_N, i));
          o[i].push_back(component(sample.output_N, i));
        }
        // The passivity observer: the work the handle's motion did against the commanded force.
        if (have_previous) {
          for (int i = 0; i < N; ++i) {
            energy_J -= component(previous.output_N, i) * (component(sample.x_m, i) - component(previous.x_m, i));
          }
        }
        previous = sample;
        have_previous = true;
      }
      // Script faults, each once, as the tap copied them.
      json new_faults = json::array();
      StreamScriptFault fault;
      while (tap.pop_fault(&fault)) new_faults.push_back(fault_json(fault));
      // The device's links: the newest counters the tap took.
      bool health_fresh = false;
      while (tap.pop_link_health(&health)) health_fresh = true;
      const json links = links_json(health_fresh);
      const auto now = Clock::now();
      const std::uint64_t ticks = tap.ticks();
      const double dt_s = std::chrono::duration<double>(now - last_time).count();
      if (dt_s > 0.0) {
        const double instant_hz = static_cast<double>(ticks - last_ticks) / dt_s;
        rate_hz = rate_hz == 0.0 ? instant_hz : 0.8 * rate_hz + 0.2 * instant_hz;
      }
      last_ticks = ticks;
      last_time = now;

      json event{{"seq", seq.load()}, {"tick", first_tick}, {"stride", tap.stride()}, {"t_s", t_s}};
      if constexpr (N == 1) {
        event["x_m"] = x[0];
        event["force_N"] = f[0];
        event["output_N"] = o[0];
      } else {
        event["x_m"] = x[0];
        event["y_m"] = x[1];
        event["force_x_N"] = f[0];
        event["force_y_N"] = f[1];
        event["output_x_N"] = o[0];
        event["output_y_N"] = o[1];
        json proxies = json::array();
        for (std::size_t i = 0; i < previous.proxy_count; ++i) proxies.push_back(axes_json(previous.proxies_m[i]));
        event["proxies_m"] = proxies;
      }
      const SafetyCounters& safety = previous.safety;
      json status{{"ticks", ticks},
                  {"t_s", static_cast<double>(ticks) * period_s},
                  {"loop_rate_hz", rate_hz},
                  {"energy_J", energy_J},
                  {"dropped_ticks", tap.dropped()},
                  {"finished", tap.finished()},
                  {"safety",
                   {{"clamped_ticks", safety.clamped_ticks},
                    {"slew_limited_ticks", safety.slew_limited_ticks},
                    {"soft_start_ticks", safety.soft_start_ticks},
                    {"outside_workspace_ticks", safety.outside_workspace_ticks},
                    {"nonfinite_faults", safety.nonfinite_faults},
                    {"position_hold_ticks", safety.position_hold_ticks},
                    {"pose_hold_ticks", safety.pose_hold_ticks},
                    {"motor_saturated_ticks", safety.motor_saturated_ticks}}}};
      if (monitor != nullptr) {
        status["deadline_misses"] = monitor->deadline_misses();
        status["overrun_warnings"] = monitor->overrun_warnings();
        status["wake_late_max_us"] = static_cast<double>(monitor->take_wake_late_max_ns()) * 1e-3;
        status["compute_max_us"] = static_cast<double>(monitor->take_compute_max_ns()) * 1e-3;
      } else {
        status["deadline_misses"] = nullptr;
        status["overrun_warnings"] = nullptr;
        status["wake_late_max_us"] = nullptr;
        status["compute_max_us"] = nullptr;
      }
      json disabled = json::array();
      for (int i = 0; i < 64; ++i) {
        if ((previous.scripts_disabled >> i) & 1u) disabled.push_back(i);
      }
      status["scripts_disabled"] = disabled;
      status["script_faults"] = tap.faults_seen();
      status["links"] = links;
      event["status"] = status;
      event["script_faults"] = new_faults;
      // The event, with each client's own count of dropped events at the end. After the
      // run's last event ("event: end") nothing more is sent.
      std::lock_guard lock(clients_mutex);
      if (ended.load()) continue;
      // An overrun limit passed that did not stop the run (a simulated device): said once.
      if (monitor != nullptr && monitor->overrun_kind() != OverrunFault::none && !overrun_logged) {
        overrun_logged = true;
        if (!monitor->overrun_stopped()) pending_log.push_back(overrun_text(*monitor));
      }
      event["log"] = json(pending_log);
      for (std::string& line : pending_log) {
        if (log_history.size() >= kLiveLogHistory) log_history.pop_front();
        log_history.push_back(std::move(line));
      }
      pending_log.clear();
      for (const json& new_fault : new_faults) {
        if (fault_history.size() >= kLiveClientQueue) fault_history.erase(fault_history.begin());
        fault_history.push_back(new_fault);
      }
      std::string body = event.dump();
      body.pop_back();  // the closing brace: each client's count follows
      const bool finishing = tap.finished() && !any && !ended;
      // How the run ended, with the terminal's words for a fault (docs/reference/live-view-api.md).
      const std::string end_data = finishing && monitor != nullptr ? run_end_json(*monitor).dump() : "{}";
      for (const auto& client : clients) {
        if (client->queue.size() >= kLiveClientQueue) {
          client->queue.pop_front();
          ++client->dropped;
          ++dropped_events_total;
        }
        std::string event_text = "id: " + std::to_string(seq.load()) + "\ndata: " + body + ",\"dropped_events\":" +
                           std::to_string(client->dropped) + "}\n\n";
        if (finishing) event_text += "event: end\ndata: " + end_data + "\n\n";
        client->queue.push_back(std::move(event_text));
      }
      if (finishing) ended.store(true);
      ++seq;
      clients_cv.notify_all();
    }
  }

  UiAddress address;
  std::string path;
  std::string base_dir;
  GatedServer server;
  int bound_port{-1};
  std::atomic<bool> listen_ended{false};
  std::string token;
  StreamTapOf<N> tap;
  double period_s{};
  ReloadWatcherOf<N>* watcher{};
  LoopMonitor* monitor{};

  std::mutex doc_mutex;  // text, file_text, file_stamp, parameters, scene_json
  std::string text;      // the current values: what save writes
  std::string file_text; // the file as last read or written
  std::filesystem::file_time_type file_stamp{};
  std::uint64_t seen_file_versions{};  // the watcher's file_versions() when last read
  std::vector<LiveParameter> parameters;
  json scene_json;
  std::uint64_t changes{};

  std::mutex clients_mutex;  // clients, their queues, pending_log, log_history
  std::condition_variable clients_cv;
  std::vector<std::shared_ptr<LiveStreamClient>> clients;
  std::vector<std::string> pending_log;
  std::deque<std::string> log_history;  // the last kLiveLogHistory lines sent, for new clients
  std::uint64_t dropped_events_total{};

  std::vector<std::string> link_names;  // the device's boards (set before serving)
  HandPointerOf<N>* pointer{};           // a simulated device's hand, for POST /api/hand (set before serving)
  std::vector<json> fault_history;      // the run's script faults (the last kLiveClientQueue), with clients_mutex

  // The pump thread's own.
  DeviceLinkHealth health{};
  DeviceLinkHealth health_before{};
  json last_mean_us[kMaxDeviceLinks]{};
  StreamSampleOf<N> previous{};
  bool have_previous{};
  double energy_J{};
  std::atomic<std::uint64_t> seq{0};

  std::mutex validate_mutex;
  std::atomic<bool> stopping{false};
  std::atomic<bool> ended{false};  // the "end" event was queued
  bool overrun_logged{false};      // pump thread: a passed overrun limit went to the log
  std::thread server_thread;
  std::thread pump_thread;
};

template <int N>
LiveViewOf<N>::LiveViewOf(const UiAddress& address, std::string environment_path, const SceneOf<N>& scene)
    : impl_(std::make_unique<Impl>(address, std::move(environment_path), scene)) {}

template <int N>
LiveViewOf<N>::~LiveViewOf() {
  stop();
}

template <int N>
void LiveViewOf<N>::stop() {
  Impl& s = *impl_;
  // The streams' last event, when the run is over: the pump sends it within two periods.
  for (int i = 0; i < 20 && s.tap.finished() && !s.ended.load() && s.pump_thread.joinable(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Let the clients' writers take what is queued.
  for (int i = 0; i < 20 && s.pump_thread.joinable(); ++i) {
    bool empty = true;
    {
      std::lock_guard lock(s.clients_mutex);
      for (const auto& client : s.clients) empty = empty && client->queue.empty();
    }
    if (empty) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Nothing waits for a client from here on: handlers see `stopping` (a load or validate
  // still running is abandoned), every connection is shut, and the accept loop ends.
  s.stopping.store(true);
  s.clients_cv.notify_all();
  if (s.pump_thread.joinable()) s.pump_thread.join();
  // The streams end their responses themselves (the last chunk written) unless a client
  // does not read: at most 300 ms.
  for (int i = 0; i < 30; ++i) {
    {
      std::lock_guard lock(s.clients_mutex);
      if (s.clients.empty()) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  s.server.close_connections();
  if (s.server_thread.joinable()) {
    // httplib's stop() does nothing before its accept loop has begun.
    while (!s.server.is_running() && !s.listen_ended.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    s.server.stop();
    s.server_thread.join();
  }
  // The scripted hand again, whatever a page left (no request can come any more).
  if (s.pointer != nullptr) s.pointer->release();
}

template <int N>
void LiveViewOf<N>::start(ReloadWatcherOf<N>* watcher, LoopMonitor* monitor, const DeviceOf<N>* device) {
  Impl& s = *impl_;
  s.watcher = watcher;
  s.monitor = monitor;
  s.tap.set_device(device);
  if (device != nullptr) s.link_names = device->link_names();
  if (device != nullptr) s.pointer = device->hand_pointer();
  httplib::Server& server = s.server;
  // Checked before routing and before any body is read: the token, then the endpoint
  // (anything else is answered with its body unread, and the connection closed), then
  // a declared length over the bound.
  server.set_pre_routing_handler([&s](const httplib::Request& req, httplib::Response& res) {
    std::string given = req.get_param_value("token");
    const std::string authorization = req.get_header_value("Authorization");
    if (given.empty() && authorization.rfind("Bearer ", 0) == 0) given = authorization.substr(7);
    res.set_header("Cache-Control", "no-store");
    const auto refuse = [&](int status, const std::string& message) {
      GatedServer::close_after_response();
      error_response(res, status, message);
      return httplib::Server::HandlerResponse::Handled;
    };
    if (!same_token(given, s.token)) {
      return refuse(403, "forbidden: the token is missing or wrong (open the URL `hapscene run --ui` printed)");
    }
    const bool get = req.path == "/" || req.path == "/api/scene" || req.path == "/api/stream";
    const bool post = req.path == "/api/params" || req.path == "/api/save" || req.path == "/api/validate" ||
                      req.path == "/api/hand";
    if (!get && !post) return refuse(404, "not found: " + req.path);
    if (req.method != (get ? "GET" : "POST")) return refuse(405, req.method + " " + req.path + ": expected " + (get ? "GET" : "POST"));
    const bool has_body = req.has_header("Content-Length") || req.has_header("Transfer-Encoding");
    if (get && has_body) GatedServer::close_after_response();  // a body a GET never reads
    if (req.has_header("Content-Length")) {
      const std::string length = req.get_header_value("Content-Length");
      if (length.size() > 18 || std::strtoull(length.c_str(), nullptr, 10) > kMaxRequestBodyBytes) {
        return refuse(413, "request body: larger than " + std::to_string(kMaxRequestBodyBytes) + " bytes");
      }
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    GatedServer::request_arrived();
    res.set_content(live_page_html(), "text/html; charset=utf-8");
  });
  server.Get("/api/scene", [&s](const httplib::Request&, httplib::Response& res) {
    GatedServer::request_arrived();
    std::lock_guard lock(s.doc_mutex);
    s.refresh_from_file();
    res.set_content(s.scene_with_state().dump(), "application/json");
  });
  server.Get("/api/stream", [&s](const httplib::Request&, httplib::Response& res) {
    GatedServer::request_arrived();
    s.stream(res);
  });
  // The posts read their bodies themselves, bounded (read_body), then act.
  const auto post = [&server](const char* path, std::function<void(const std::string&, httplib::Response&)> act) {
    server.Post(path, [act = std::move(act)](const httplib::Request& req, httplib::Response& res,
                                             const httplib::ContentReader& reader) {
      std::string body;
      if (!read_body(req, res, reader, &body)) return;
      GatedServer::request_arrived();
      act(body, res);
    });
  };
  post("/api/params", [&s](const std::string& body, httplib::Response& res) { s.change(body, res); });
  post("/api/save", [&s](const std::string&, httplib::Response& res) { s.save(res); });
  post("/api/validate", [&s](const std::string&, httplib::Response& res) { s.validate(res); });
  post("/api/hand", [&s](const std::string& body, httplib::Response& res) { s.hand(body, res); });
  // httplib's own answers (a malformed request: 400) carry a JSON error too.
  server.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    error_response(res, res.status, "request refused (HTTP " + std::to_string(res.status) + ")");
    return httplib::Server::HandlerResponse::Handled;
  }));
  s.server_thread = std::thread([&s] {
    s.server.listen_after_bind();
    s.listen_ended.store(true);
  });
  s.pump_thread = std::thread([&s] { s.pump(); });
}

template <int N>
TickObserverOf<N>* LiveViewOf<N>::tap() {
  return &impl_->tap;
}

template <int N>
void LiveViewOf<N>::add_log(const std::string& line) {
  std::lock_guard lock(impl_->clients_mutex);
  if (impl_->pending_log.size() < 1000) impl_->pending_log.push_back(line);
}

template <int N>
std::string LiveViewOf<N>::url() const {
  const std::string& host = impl_->address.host;
  const std::string shown = host.find(':') != std::string::npos ? "[" + host + "]" : host;
  return "http://" + shown + ":" + std::to_string(impl_->bound_port) + "/?token=" + impl_->token;
}

template <int N>
const std::string& LiveViewOf<N>::token() const {
  return impl_->token;
}

template <int N>
int LiveViewOf<N>::port() const {
  return impl_->bound_port;
}

template <int N>
std::uint64_t LiveViewOf<N>::dropped_events() const {
  std::lock_guard lock(impl_->clients_mutex);
  return impl_->dropped_events_total;
}

template <int N>
std::uint64_t LiveViewOf<N>::dropped_ticks() const {
  return impl_->tap.dropped();
}

template <int N>
std::uint64_t LiveViewOf<N>::events_sent() const {
  return impl_->seq.load();
}

#define HAPSCENE_LIVE_VIEW(N) template class LiveViewOf<N>;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_LIVE_VIEW)
#undef HAPSCENE_LIVE_VIEW

}  // namespace hapscene
