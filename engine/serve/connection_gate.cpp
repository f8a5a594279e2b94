#include "engine/serve/connection_gate.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <list>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace hapscene {
namespace {

using Clock = std::chrono::steady_clock;

// Seconds an idle kept-alive connection waits for its next request.
constexpr int kKeepAlive_s = 1;

// The address of `fd`'s peer (or its own end) without the port, and the port.
void address_of(int fd, bool peer, std::string* ip, int* port) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  const int got = peer ? ::getpeername(fd, reinterpret_cast<sockaddr*>(&address), &length)
                       : ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ip->clear();
  *port = 0;
  if (got != 0) return;
  char text[INET6_ADDRSTRLEN] = {};
  if (address.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&address);
    ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
    *port = ntohs(v4->sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&address);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
    *port = ntohs(v6->sin6_port);
  }
  *ip = text;
}

// Waits until `fd` has `events` (POLLIN, POLLOUT), at most `wait_ms`.
bool wait_for(int fd, short events, int wait_ms) {
  pollfd p{fd, events, 0};
  for (;;) {
    const int got = ::poll(&p, 1, std::max(wait_ms, 0));
    if (got < 0 && errno == EINTR) continue;
    return got > 0;
  }
}

int milliseconds_of(time_t sec, time_t usec) { return static_cast<int>(sec * 1000 + usec / 1000); }

}  // namespace

// The connections open now, their counts, and the threads serving them.
struct GatedServer::Gate {
  enum class Phase { reading, handling, streaming };
  struct Connection {
    int fd{-1};
    std::string peer;
    Phase phase{Phase::reading};
    Clock::time_point deadline{};  // of the request being read
    bool close_after{};
  };

  explicit Gate(ConnectionLimits l) : limits(l) {}

  Clock::duration request_time() const {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limits.request_s));
  }
  // With the mutex held: no connection is served any more, and every open one is shut.
  void shut_all() {
    shutting_down = true;
    for (Connection& c : open) ::shutdown(c.fd, SHUT_RDWR);
    changed.notify_all();
  }

  ConnectionLimits limits;
  mutable std::mutex mutex;
  std::condition_variable changed;  // a connection's thread ended
  std::list<Connection> open;
  std::map<std::string, int> requests_of;  // per peer, streams apart
  std::map<std::string, int> streams_of;
  int requests{};
  int streams{};
  int threads{};  // started and not yet ended
  bool shutting_down{};
  std::uint64_t refused{};
  std::atomic<std::uint64_t> slow_closed{0};
};

namespace {

using Gate = GatedServer::Gate;

// Set on the accept thread while it closes a connection over the thread limit.
thread_local bool t_refuse = false;
// The connection this thread serves.
thread_local Gate::Connection* t_connection = nullptr;
thread_local Gate* t_gate = nullptr;

// httplib's task queue, replaced: a thread per connection, as many as the limits allow.
class GateQueue : public httplib::TaskQueue {
 public:
  explicit GateQueue(std::shared_ptr<Gate> gate) : gate_(std::move(gate)) {}
  ~GateQueue() override { shutdown(); }

  void enqueue(std::function<void()> fn) override {
    {
      std::lock_guard lock(gate_->mutex);
      if (!gate_->shutting_down && gate_->threads < gate_->limits.total + gate_->limits.streams_total) {
        ++gate_->threads;
        std::thread([gate = gate_, fn = std::move(fn)]() mutable {
          fn();
          fn = nullptr;
          std::lock_guard ended(gate->mutex);
          --gate->threads;
          gate->changed.notify_all();
        }).detach();
        return;
      }
    }
    // Over the limit: closed here and now, unread.
    t_refuse = true;
    fn();
    t_refuse = false;
  }

  // After the accept loop ended: every connection shut, their threads waited for.
  void shutdown() override {
    std::unique_lock lock(gate_->mutex);
    gate_->shut_all();
    gate_->changed.wait(lock, [&] { return gate_->threads == 0; });
  }

 private:
  std::shared_ptr<Gate> gate_;
};

// A connection's bytes, as httplib reads and writes them: reads wait at most until the
// request's deadline while it is being read (then fail: the request is over), writes at
// most the write timeout.
class GateStream : public httplib::Stream {
 public:
  GateStream(int fd, Gate& gate, Gate::Connection& connection, int read_ms, int write_ms)
      : fd_(fd), gate_(gate), connection_(connection), read_ms_(read_ms), write_ms_(write_ms) {}

  bool is_readable() const override {
    const int wait_ms = read_wait_ms();
    return wait_ms > 0 && wait_for(fd_, POLLIN, wait_ms);
  }
  bool is_writable() const override { return wait_for(fd_, POLLOUT, write_ms_); }

  ssize_t read(char* ptr, size_t size) override {
    if (begin_ < end_) {
      const std::size_t n = std::min(size, end_ - begin_);
      std::memcpy(ptr, buffer_ + begin_, n);
      begin_ += n;
      return static_cast<ssize_t>(n);
    }
    if (!is_readable()) return -1;
    char* into = size < sizeof buffer_ ? buffer_ : ptr;
    const std::size_t room = size < sizeof buffer_ ? sizeof buffer_ : size;
    ssize_t got;
    do {
      got = ::recv(fd_, into, room, 0);
    } while (got < 0 && errno == EINTR);
    if (got <= 0 || into == ptr) return got;
    begin_ = 0;
    end_ = static_cast<std::size_t>(got);
    return read(ptr, size);
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    ssize_t sent;
    do {
      sent = ::send(fd_, ptr, size, MSG_NOSIGNAL);
    } while (sent < 0 && errno == EINTR);
    return sent;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override { address_of(fd_, true, &ip, &port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address_of(fd_, false, &ip, &port); }
  socket_t socket() const override { return fd_; }
  // A request did not arrive in time on this connection.
  bool late() const { return late_; }

 private:
  // How long a read may wait now: the read timeout, or less while a request is being read.
  int read_wait_ms() const {
    if (connection_.phase != Gate::Phase::reading) return read_ms_;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(connection_.deadline - Clock::now()).count();
    if (left <= 0) {
      if (!late_) ++gate_.slow_closed;
      late_ = true;
      return 0;
    }
    return static_cast<int>(std::min<long long>(left, read_ms_));
  }

  int fd_;
  Gate& gate_;
  Gate::Connection& connection_;
  int read_ms_;
  int write_ms_;
  mutable bool late_{};
  char buffer_[4096];
  std::size_t begin_{};
  std::size_t end_{};
};

}  // namespace

GatedServer::GatedServer(ConnectionLimits limits) : gate_(std::make_shared<Gate>(limits)) {
  new_task_queue = [gate = gate_] { return new GateQueue(gate); };
  set_keep_alive_timeout(kKeepAlive_s);
}

GatedServer::~GatedServer() = default;

bool GatedServer::process_and_close_socket(socket_t sock) {
  Gate& gate = *gate_;
  const auto close_now = [&] {
    ::shutdown(sock, SHUT_RDWR);
    ::close(sock);
  };
  std::string peer;
  int port = 0;
  address_of(sock, true, &peer, &port);
  std::list<Gate::Connection>::iterator connection;
  {
    std::lock_guard lock(gate.mutex);
    if (t_refuse || gate.shutting_down || gate.requests >= gate.limits.total ||
        gate.requests_of[peer] >= gate.limits.per_peer) {
      ++gate.refused;
      if (gate.requests_of[peer] == 0 && gate.streams_of[peer] == 0) {
        gate.requests_of.erase(peer);
        gate.streams_of.erase(peer);
      }
      close_now();
      return false;
    }
    connection = gate.open.insert(gate.open.end(), Gate::Connection{sock, peer, Gate::Phase::reading,
                                                                    Clock::now() + gate.request_time(), false});
    ++gate.requests;
    ++gate.requests_of[peer];
  }
  Gate::Connection& c = *connection;
  t_connection = &c;
  t_gate = &gate;
  GateStream stream(sock, gate, c, milliseconds_of(read_timeout_sec_, read_timeout_usec_),
                    milliseconds_of(write_timeout_sec_, write_timeout_usec_));
  // Requests one after the other while the client keeps the connection (at most
  // keep_alive_max_count_), each with its own deadline from its first byte.
  bool served = false;
  for (std::size_t count = keep_alive_max_count_; count > 0 && svr_sock_ != INVALID_SOCKET; --count) {
    if (count != keep_alive_max_count_) {
      if (!wait_for(sock, POLLIN, kKeepAlive_s * 1000)) break;
      std::lock_guard lock(gate.mutex);
      c.deadline = Clock::now() + gate.request_time();
    }
    bool closed = false;
    served = process_request(stream, count == 1, closed, nullptr);
    {
      std::lock_guard lock(gate.mutex);
      if (c.phase == Gate::Phase::streaming) {
        --gate.streams;
        --gate.streams_of[peer];
        ++gate.requests;
        ++gate.requests_of[peer];
      }
      c.phase = Gate::Phase::reading;
    }
    if (!served || closed || c.close_after || stream.late()) break;
  }
  t_connection = nullptr;
  t_gate = nullptr;
  // Closed with the mutex held: a shut_all() never reaches a descriptor number reused.
  std::lock_guard lock(gate.mutex);
  close_now();
  --gate.requests;
  --gate.requests_of[peer];
  if (gate.requests_of[peer] == 0 && gate.streams_of[peer] == 0) {
    gate.requests_of.erase(peer);
    gate.streams_of.erase(peer);
  }
  gate.open.erase(connection);
  return served;
}

void GatedServer::request_arrived() {
  if (t_connection == nullptr) return;
  std::lock_guard lock(t_gate->mutex);
  if (t_connection->phase == Gate::Phase::reading) t_connection->phase = Gate::Phase::handling;
}

bool GatedServer::become_stream() {
  if (t_connection == nullptr) return true;
  Gate& gate = *t_gate;
  Gate::Connection& c = *t_connection;
  std::lock_guard lock(gate.mutex);
  if (c.phase == Gate::Phase::streaming) return true;
  if (gate.streams >= gate.limits.streams_total || gate.streams_of[c.peer] >= gate.limits.streams_per_peer) return false;
  --gate.requests;
  --gate.requests_of[c.peer];
  ++gate.streams;
  ++gate.streams_of[c.peer];
  c.phase = Gate::Phase::streaming;
  return true;
}

void GatedServer::close_after_response() {
  if (t_connection == nullptr) return;
  std::lock_guard lock(t_gate->mutex);
  t_connection->close_after = true;
}

void GatedServer::close_connections() {
  std::lock_guard lock(gate_->mutex);
  gate_->shut_all();
}

std::uint64_t GatedServer::refused_connections() const {
  std::lock_guard lock(gate_->mutex);
  return gate_->refused;
}

std::uint64_t GatedServer::slow_requests_closed() const { return gate_->slow_closed.load(); }

int GatedServer::open_connections() const {
  std::lock_guard lock(gate_->mutex);
  return static_cast<int>(gate_->open.size());
}

}  // namespace hapscene
