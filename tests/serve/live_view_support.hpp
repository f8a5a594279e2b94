#pragma once
// The live view's tests: a real simulated run in real time on a thread of its own, with
// the reload watcher and the live view as `hapscene run --ui` sets them up, and an HTTP
// client (cpp-httplib's) to talk to it.
#include <httplib.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/devices/open_device.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/reload_watcher.hpp"
#include "engine/run/runner.hpp"
#include "engine/serve/live_view.hpp"
#include "tests/scratch_folder.hpp"

namespace hapscene::test {

// One SSE event as read from the stream: its fields by name ("id", "event", "data").
struct SseEvent {
  std::string id;
  std::string event{"message"};
  std::string data;
};

// Splits a text/event-stream body into events (comments dropped).
inline std::vector<SseEvent> parse_sse(const std::string& body, std::string* rest = nullptr) {
  std::vector<SseEvent> events;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = body.find("\n\n", start);
    if (end == std::string::npos) break;
    SseEvent event;
    bool any = false;
    std::size_t line_start = start;
    while (line_start < end) {
      std::size_t line_end = body.find('\n', line_start);
      if (line_end == std::string::npos || line_end > end) line_end = end;
      const std::string line = body.substr(line_start, line_end - line_start);
      line_start = line_end + 1;
      if (line.empty() || line[0] == ':') continue;
      const auto colon = line.find(": ");
      const std::string field = line.substr(0, colon);
      const std::string value = colon == std::string::npos ? "" : line.substr(colon + 2);
      if (field == "id") event.id = value;
      if (field == "event") event.event = value;
      if (field == "data") event.data += value;
      any = true;
    }
    if (any) events.push_back(event);
    start = end + 2;
  }
  if (rest != nullptr) *rest = body.substr(start);
  return events;
}

// A plain TCP connection to the live view, for clients httplib's would not be: slow,
// half-sent, oversized. Never throws; a closed or failed connection reads as closed.
struct RawConnection {
  int fd{-1};
  explicit RawConnection(int port) {
    fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
      ::close(fd);
      fd = -1;
    }
  }
  ~RawConnection() {
    if (fd >= 0) ::close(fd);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;
  // False once the connection is closed or failed.
  bool send(const std::string& bytes) const {
    return fd >= 0 && ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
  }
  // What arrives within `wait_ms` (appended to `into`); false when the server closed it.
  bool receive(std::string* into, int wait_ms) const {
    if (fd < 0) return false;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, wait_ms) <= 0) return true;
    char buffer[65536];
    const ssize_t got = ::recv(fd, buffer, sizeof buffer, 0);
    if (got <= 0) return false;
    into->append(buffer, static_cast<std::size_t>(got));
    return true;
  }
  // Everything until the server closes the connection (at most `wait_ms` in all).
  std::string read_to_close(int wait_ms) const {
    std::string out;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(wait_ms);
    while (std::chrono::steady_clock::now() < until && receive(&out, 50)) {
    }
    return out;
  }
};

// A run of the environment `file` (N axes) for `duration_s` in real time with its live view.
template <int N>
struct LiveRun {
  std::string file;
  SceneOf<N> scene;
  std::unique_ptr<DeviceOf<N>> device;
  SceneExchangeOf<N> exchange;
  LoopMonitor monitor;
  std::unique_ptr<ReloadWatcherOf<N>> watcher;
  std::unique_ptr<LiveViewOf<N>> view;
  RunSummaryOf<N> summary;
  std::atomic<bool> stop{false};
  std::thread loop;

  // `device_spec`: as --device gives it ("sim", "hil").
  LiveRun(const std::string& path, double duration_s, double hold_m = 0.02, const std::string& device_spec = "sim")
      : file(path) {
    if constexpr (N == 1) {
      scene = load_environment_file(file);
      SimulationConfig simulation;
      simulation.hand.motion = HandMotion::hold;
      simulation.hand.hold_m = hold_m;
      device = open_device(device_spec, scene.device, simulation);
    } else {
      scene = load_planar_environment_file(file);
      PlanarSimulationConfig simulation;
      simulation.start_q_rad = planar_joint_angles_at(scene.device, scene.device.home_m);
      device = open_planar_device(device_spec, scene.device, simulation);
    }
    ReloadWatcherOptionsOf<N> watch;
    watch.poll_period_s = 0.05;
    watcher = std::make_unique<ReloadWatcherOf<N>>(file, scene, &exchange, [](const std::string&) {}, watch);
    view = std::make_unique<LiveViewOf<N>>(UiAddress{}, file, scene);
    view->start(watcher.get(), &monitor, device.get());
    RunOptions options;
    options.duration_s = duration_s;
    options.pacing = Pacing::real_time;
    options.stop_requested = &stop;
    options.monitor = &monitor;
    // The firmware on simavr runs about 3x slower than real time on a loaded 2-core
    // machine: every tick is late, which would end the run on the overrun fault within
    // 10 ms. The link's counters are what the hil tests look at, so the run goes on late.
    if (device_spec.starts_with("hil")) options.overruns = OverrunResponse::report;
    set_reload_exchange<N>(&options, &exchange);
    loop = std::thread([this, options] { summary = run_scene(scene, *device, options, view->tap()); });
  }
  ~LiveRun() {
    stop.store(true);
    if (loop.joinable()) loop.join();
    view->stop();
  }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", view->port());
    c.set_read_timeout(5, 0);
    return c;
  }
  std::string with_token(const std::string& path) const { return path + "?token=" + view->token(); }

  // The stream's events for `seconds` (at most), as one client sees them.
  std::vector<SseEvent> stream_for(double seconds) const {
    httplib::Client c = client();
    std::string body;
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    c.Get(with_token("/api/stream"), [&](const char* data, std::size_t length) {
      body.append(data, length);
      return std::chrono::steady_clock::now() < until && body.find("event: end") == std::string::npos;
    });
    return parse_sse(body);
  }

  nlohmann::json post_params(const nlohmann::json& request, int* status) const {
    httplib::Client c = client();
    const auto result = c.Post(with_token("/api/params"), request.dump(), "application/json");
    *status = result ? result->status : -1;
    return result ? nlohmann::json::parse(result->body) : nlohmann::json();
  }
};

}  // namespace hapscene::test
