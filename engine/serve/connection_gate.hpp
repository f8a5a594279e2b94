#pragma once
// The live view's HTTP server (cpp-httplib's Server) with bounds on what its clients can
// hold, so that no client, with the token or without, can keep the page from answering
// or the run from ending:
// - every connection has a thread of its own, started at accept; a connection over the
//   limits (per peer address, in all) is closed at once, before it is read;
// - a request (line, headers, body) must arrive within `request_s` of the connection's
//   start or of its first byte, else the connection is closed (one byte every few
//   seconds keeps no thread); an idle kept-alive connection is closed after 1 s;
// - a stream (GET /api/stream) leaves the requests' budget for a budget of its own, so
//   open streams never take the threads the page needs;
// - stop() (httplib's) ends the accept loop, then every open connection is shut at once
//   and the connections' threads are waited for: a handler that sees its socket shut, or
//   the live view stopping, returns at once, so this takes milliseconds.
// httplib's own ThreadPool is not used (its 8 workers are what slow clients took), nor its
// socket stream: the connection's bytes go through a stream of ours that knows the
// request's deadline.
#include <httplib.h>

#include <cstdint>
#include <memory>

namespace hapscene {

struct ConnectionLimits {
  int per_peer{16};         // connections one address may have open, streams apart
  int total{32};            // all addresses together, streams apart
  int streams_per_peer{8};  // streams one address may have open
  int streams_total{16};
  double request_s{2.0};    // a request must arrive within this (see above)
};

class GatedServer : public httplib::Server {
 public:
  explicit GatedServer(ConnectionLimits limits = {});
  ~GatedServer() override;

  // On a handler's thread (the connection being served): the request has arrived whole;
  // the handler's own work has no deadline.
  static void request_arrived();
  // On a handler's thread: this connection is a stream from now on. False when the
  // streams' limits are reached (answer 503 then).
  static bool become_stream();
  // On a handler's thread: the connection is closed once this response is out (a request
  // answered without reading its body).
  static void close_after_response();

  // Counts: connections refused at once (over a limit), closed for a request that did
  // not arrive in time, open now (streams included).
  std::uint64_t refused_connections() const;
  std::uint64_t slow_requests_closed() const;
  int open_connections() const;

  // Shuts every open connection now (their handlers see the socket closed). The live
  // view calls it when it stops, before httplib's stop().
  void close_connections();

  struct Gate;

 protected:
  bool process_and_close_socket(socket_t sock) override;

 private:
  std::shared_ptr<Gate> gate_;
};

}  // namespace hapscene
