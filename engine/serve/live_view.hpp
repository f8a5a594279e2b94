#pragma once
// `hapscene run --ui`: the live view. An HTTP server (cpp-httplib) on its own threads
// serves the page (ui/, compiled in), the scene and its parameters, a Server-Sent Events
// stream of the ticks, parameter changes and saving, and a validate run. It reads the
// loop only through a StreamTap (a lock-free ring the loop pushes into) and a
// LoopMonitor (relaxed atomics), and hands parameter changes to the run's ReloadWatcher
// (the same load, check and cross-fade as a hot reload of the file). Nothing here is
// ever waited for by the loop.
//
// Endpoints (every one needs the token: ?token=T or "Authorization: Bearer T"):
//   GET  /              the page
//   GET  /api/scene     the scene: device, limits, effects, parameters, 2-D shapes
//   GET  /api/stream    text/event-stream; one event every 1/kLiveEventsPerSecond s
//   POST /api/params    {"effect": I, "parameter": NAME, "value": V}: 200 taken, 400 refused
//   POST /api/save      writes the values back to the environment file
//   POST /api/validate  runs the harness on the current values; the verdict table
// (docs/reference/live-view-api.md gives the formats.) Clients are bounded (engine/serve/connection_gate.hpp):
// per address and in all, the time a request may take to arrive, streams apart from the
// page's requests, request bodies at 64 KiB however they are sent (413); loads and
// validate runs go on threads of their own that stop() abandons, so stop() never waits
// for a client.
#include <cstdint>
#include <memory>
#include <string>

#include "engine/devices/device.hpp"
#include "engine/run/loop_monitor.hpp"
#include "engine/run/reload_watcher.hpp"
#include "engine/run/tick_observer.hpp"
#include "engine/scene/scene.hpp"
#include "engine/serve/ui_address.hpp"

namespace hapscene {

// Events per second of /api/stream (each carries every tick since the one before).
inline constexpr double kLiveEventsPerSecond = 50.0;
// Most ticks per second the stream carries: above, every stride-th tick (stride =
// ceil(rate / this)).
inline constexpr double kLiveMaxTicksPerSecond = 2000.0;
// Events a client may fall behind before its oldest are dropped (and counted).
inline constexpr std::size_t kLiveClientQueue = 64;
// Log lines a stream's new client gets first (what the page keeps: the same 200).
inline constexpr std::size_t kLiveLogHistory = 200;

// Loads and validate runs the live views of this process abandoned when they stopped
// (their threads may still run: the process should then end with std::_Exit after
// flushing its output).
std::uint64_t abandoned_live_view_jobs() noexcept;

// The stride of the stream for a scene of `rate_hz`.
std::uint64_t live_stride(double rate_hz);

template <int N>
class LiveViewOf {
 public:
  // Binds the address (InputError when it cannot: "--ui 127.0.0.1:80: cannot listen
  // there"), reads the environment file's text; serves nothing until start().
  LiveViewOf(const UiAddress& address, std::string environment_path, const SceneOf<N>& scene);
  // Stops the server and its threads (open streams end).
  ~LiveViewOf();
  LiveViewOf(const LiveViewOf&) = delete;
  LiveViewOf& operator=(const LiveViewOf&) = delete;

  // Starts serving; parameter changes go to `watcher` (not null), the loop's timing is
  // read from `monitor` (may be null), the link counters of `device` (may be null) are
  // taken by the tap on the loop's thread. Before the run starts.
  void start(ReloadWatcherOf<N>* watcher, LoopMonitor* monitor, const DeviceOf<N>* device = nullptr);

  // Ends the streams (after their last event, "event: end", when the run has finished)
  // and stops serving, within half a second whatever the clients do; after it, nothing
  // uses the watcher any more. Idempotent.
  void stop();

  // The observer to add to the run (before it starts).
  TickObserverOf<N>* tap();
  // A line for the page's log (reload messages, script log lines). Any thread.
  void add_log(const std::string& line);

  // "http://127.0.0.1:PORT/?token=TOKEN"
  std::string url() const;
  const std::string& token() const;
  int port() const;
  // Events dropped because a client fell behind, summed over clients; ticks dropped
  // because the ring was full.
  std::uint64_t dropped_events() const;
  std::uint64_t dropped_ticks() const;
  std::uint64_t events_sent() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

using LiveView = LiveViewOf<1>;

}  // namespace hapscene
