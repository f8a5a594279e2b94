#include "engine/serve/live_view.hpp"

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/serve/connection_gate.hpp"
#include "engine/serve/live_document.hpp"
#include "engine/serve/live_hand.hpp"
#include "engine/serve/live_requests.hpp"
#include "engine/serve/live_stream.hpp"
#include "engine/serve/live_validate.hpp"
#include "engine/serve/ui_assets.hpp"

// The live view's HTTP side: the address, the token, the routes and stopping. What each
// endpoint does is its part's: the document (scene, params, save: live_document), the
// stream (live_stream), the hand (live_hand) and validate (live_validate).
namespace hapscene {

using json = nlohmann::json;

template <int N>
struct LiveViewOf<N>::Impl {
  Impl(const UiAddress& where, std::string environment_path, const SceneOf<N>& scene)
      : address(where),
        stream(scene, stopping),
        document(std::move(environment_path), scene, stream.tap().stride(), stopping) {
    token = new_token();
    server.set_payload_max_length(kMaxRequestBodyBytes);
    bound_port = address.port == 0 ? server.bind_to_any_port(address.host) : (server.bind_to_port(address.host, address.port) ? address.port : -1);
    if (bound_port < 0) {
      throw InputError("--ui " + address.host + ":" + std::to_string(address.port) + ": cannot listen there (" +
                       std::string(std::strerror(errno)) + ")");
    }
  }

  // The scene's body with the run's state: the device's boards, whether the page may move
  // the hand (POST /api/hand takes a simulated hand), the script faults so far.
  json with_run_state(json scene) {
    scene["device"]["links"] = link_names;
    scene["device"]["hand_pointer"] = pointer != nullptr;
    scene["script_faults"] = stream.fault_history();
    return scene;
  }

  // POST /api/validate, one at a time.
  void validate(httplib::Response& res) {
    std::unique_lock busy(validate_mutex, std::try_to_lock);
    if (!busy.owns_lock()) {
      error_response(res, 409, "a validate run is already running");
      return;
    }
    validate_version<N>(document.current_text(), document.path(), document.base_dir(), stopping, res);
  }

  UiAddress address;
  std::atomic<bool> stopping{false};  // the view is stopping: streams end, jobs are abandoned
  LiveStreamOf<N> stream;
  LiveDocumentOf<N> document;
  GatedServer server;
  int bound_port{-1};
  std::atomic<bool> listen_ended{false};
  std::string token;
  std::vector<std::string> link_names;  // the device's boards (set before serving)
  HandPointerOf<N>* pointer{};           // a simulated device's hand (set before serving)
  std::mutex validate_mutex;
  std::thread server_thread;
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
  s.stream.drain();
  // Nothing waits for a client from here on: handlers see `stopping` (a load or validate
  // still running is abandoned), every connection is shut, and the accept loop ends.
  s.stopping.store(true);
  s.stream.stop();
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
  s.document.set_watcher(watcher);
  s.stream.tap().set_device(device);
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
    res.set_content(s.document.scene([&s](json scene) { return s.with_run_state(std::move(scene)); }).dump(),
                    "application/json");
  });
  server.Get("/api/stream", [&s](const httplib::Request&, httplib::Response& res) {
    GatedServer::request_arrived();
    s.stream.serve(res);
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
  post("/api/params", [&s](const std::string& body, httplib::Response& res) {
    s.document.change(body, res, [&s](json scene) { return s.with_run_state(std::move(scene)); });
  });
  post("/api/save", [&s](const std::string&, httplib::Response& res) { s.document.save(res); });
  post("/api/validate", [&s](const std::string&, httplib::Response& res) { s.validate(res); });
  post("/api/hand", [&s](const std::string& body, httplib::Response& res) { move_hand(s.pointer, body, s.document, res); });
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
  s.stream.start(monitor, s.link_names);
}

template <int N>
TickObserverOf<N>* LiveViewOf<N>::tap() {
  return &impl_->stream.tap();
}

template <int N>
void LiveViewOf<N>::add_log(const std::string& line) {
  impl_->stream.add_log(line);
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
  return impl_->stream.dropped_events();
}

template <int N>
std::uint64_t LiveViewOf<N>::dropped_ticks() const {
  return impl_->stream.tap().dropped();
}

template <int N>
std::uint64_t LiveViewOf<N>::events_sent() const {
  return impl_->stream.events_sent();
}

#define HAPSCENE_LIVE_VIEW(N) template class LiveViewOf<N>;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_LIVE_VIEW)
#undef HAPSCENE_LIVE_VIEW

}  // namespace hapscene
