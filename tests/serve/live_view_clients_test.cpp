// The live view against clients that misbehave, with the token or without: slow requests,
// open streams, oversized bodies, a validate run still going when the run ends, and a
// link planted where a save used to write. Real sockets against the real server; the
// bounds are checked by counts and generous watchdogs, never by a tight stopwatch.
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/serve/live_view_support.hpp"

namespace hapscene {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

const char* kSpring = R"({
  "name": "live spring",
  "effects": [
    {"type": "spring", "stiffness": "100 N/m", "center": "0 mm"}
  ]
}
)";

// Clients that send the start of a request (no token) and then one byte every 200 ms,
// for as long as they are let: each would hold a thread of a server that only bounds the
// time between two reads.
struct SlowClients {
  std::vector<std::unique_ptr<test::RawConnection>> connections;
  std::vector<std::atomic<int>> bytes_sent;  // read by the test while the trickle writes
  std::atomic<bool> done{false};
  std::thread trickle;

  SlowClients(int port, int count) : bytes_sent(static_cast<std::size_t>(count)) {
    for (int i = 0; i < count; ++i) {
      connections.push_back(std::make_unique<test::RawConnection>(port));
      connections.back()->send("GET / HTTP/1.1\r\nHost: x\r\n");
    }
    trickle = std::thread([this] {
      while (!done.load()) {
        for (std::size_t i = 0; i < connections.size(); ++i) {
          const int sent = bytes_sent[i].load();
          if (sent < 0) continue;
          if (connections[i]->send("X")) {
            bytes_sent[i].store(sent + 1);
          } else {
            bytes_sent[i].store(-1 - sent);  // closed by the server after -n - 1 bytes
          }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
    });
  }
  void stop() {
    done.store(true);
    if (trickle.joinable()) trickle.join();
  }
  ~SlowClients() { stop(); }
};

// The status line and body of the response on `connection` (read until it closes).
std::string response_of(const test::RawConnection& connection) { return connection.read_to_close(10000); }

}  // namespace

TEST_SUITE("threaded") {

TEST_CASE("live view: slow clients and a validate still running cannot keep the run from ending (the signal's stop)") {
  test::ScratchFolder folder("live_slow_end");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 60.0);
  SlowClients slow(run.view->port(), 8);
  // A validate run, with the token, busy when the run ends.
  std::thread validator([&] {
    httplib::Client client = run.client();
    client.set_read_timeout(60, 0);
    (void)client.Post(run.with_token("/api/validate"), "", "application/json");
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  // What Ctrl-C and SIGTERM do: the loop stops at its next tick (zero force), then the view.
  run.stop.store(true);
  run.loop.join();
  const auto stop_start = Clock::now();
  auto stopped = std::async(std::launch::async, [&] { run.view->stop(); });
  const bool in_time = stopped.wait_for(std::chrono::seconds(10)) == std::future_status::ready;
  slow.stop();  // (without the bound, this is what lets stop() return at last)
  stopped.wait();
  const double stop_s = std::chrono::duration<double>(Clock::now() - stop_start).count();
  validator.join();
  MESSAGE("the view stopped in " << stop_s << " s with 8 slow clients and a validate running");
  CHECK(in_time);
  CHECK(run.summary.ticks > 0);
}

TEST_CASE("live view: a request must arrive within 2 s: a client sending a byte every 200 ms is closed") {
  test::ScratchFolder folder("live_slow_close");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 30.0);
  SlowClients slow(run.view->port(), 4);
  // Watched for up to 12 s (60 bytes): each is closed after about 10 (21 measured under a
  // load average of 15); without the bound none ever is.
  for (int i = 0; i < 60; ++i) {
    bool all_closed = true;
    for (const auto& sent : slow.bytes_sent) all_closed = all_closed && sent.load() < 0;
    if (all_closed) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  slow.stop();
  for (const auto& sent : slow.bytes_sent) {
    CHECK(sent.load() < 0);  // closed by the server
  }
}

TEST_CASE("live view: 8 slow clients and 8 open streams lock no one out, and a stream past the limit gets 503") {
  test::ScratchFolder folder("live_slow_page");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 30.0);
  SlowClients slow(run.view->port(), 8);
  std::vector<std::unique_ptr<test::RawConnection>> streams;
  const std::string stream_request = "GET " + run.with_token("/api/stream") + " HTTP/1.1\r\nHost: x\r\n\r\n";
  for (int i = 0; i < 8; ++i) {
    streams.push_back(std::make_unique<test::RawConnection>(run.view->port()));
    REQUIRE(streams.back()->send(stream_request));
    std::string head;
    for (int k = 0; k < 100 && head.find("\r\n\r\n") == std::string::npos; ++k) {
      if (!streams.back()->receive(&head, 50)) break;
    }
    CHECK(head.rfind("HTTP/1.1 200", 0) == 0);
  }
  // The page, its scene and a change are answered while all of them are open.
  httplib::Client client = run.client();
  const auto page = client.Get(run.with_token("/"));
  REQUIRE(page);
  CHECK(page->status == 200);
  const auto scene = client.Get(run.with_token("/api/scene"));
  REQUIRE(scene);
  CHECK(scene->status == 200);
  int status = 0;
  (void)run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", 150}}, &status);
  CHECK(status == 200);
  // A ninth stream from the same address is refused, with the reason.
  test::RawConnection ninth(run.view->port());
  REQUIRE(ninth.send(stream_request));
  const std::string refused = response_of(ninth);
  CHECK(refused.rfind("HTTP/1.1 503", 0) == 0);
  CHECK(refused.find("{\"error\":\"too many streams open") != std::string::npos);
}

TEST_CASE("live view: a request body is bounded however it is sent: 413 with the reason, and nothing changes") {
  test::ScratchFolder folder("live_body");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 30.0);
  const std::string expected = "{\"error\":\"request body: larger than 65536 bytes\"}";
  SUBCASE("chunked, 2 MiB") {
    test::RawConnection connection(run.view->port());
    REQUIRE(connection.send("POST " + run.with_token("/api/params") +
                            " HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n"));
    // 32 chunks of 64 KiB, sent while the answer is read (the server stops reading early).
    std::thread writer([&] {
      const std::string chunk = "10000\r\n" + std::string(65536, ' ') + "\r\n";
      for (int i = 0; i < 32 && connection.send(chunk); ++i) {
      }
      (void)connection.send("0\r\n\r\n");
    });
    const std::string response = response_of(connection);
    writer.join();
    CHECK(response.rfind("HTTP/1.1 413", 0) == 0);
    CHECK(response.find(expected) != std::string::npos);
  }
  SUBCASE("with a Content-Length of 2 MiB: refused before it is sent") {
    test::RawConnection connection(run.view->port());
    REQUIRE(connection.send("POST " + run.with_token("/api/params") +
                            " HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: 2097152\r\n\r\n"));
    const std::string response = response_of(connection);
    CHECK(response.rfind("HTTP/1.1 413", 0) == 0);
    CHECK(response.find(expected) != std::string::npos);
  }
  // The server goes on, and the parameter is as it was.
  httplib::Client client = run.client();
  const auto scene = client.Get(run.with_token("/api/scene"));
  REQUIRE(scene);
  CHECK(json::parse(scene->body)["parameters"][0]["value"] == 100.0);
}

TEST_CASE("live view: save replaces the file whole, never through a link planted next to it, and keeps its permissions") {
  test::ScratchFolder folder("live_save_link");
  const std::string file = folder.write("spring.json", kSpring).string();
  const std::string victim = folder.write("victim.txt", "precious\n").string();
  REQUIRE(::chmod(file.c_str(), 0640) == 0);
  // Links where a save might write its temporary file: the old fixed name, and others.
  for (const char* name : {"spring.json.hapscene-save", ".spring.json.tmp", "spring.json.tmp", "spring.json~"}) {
    std::filesystem::create_symlink(victim, folder.dir / name);
  }
  test::LiveRun<1> run(file, 30.0);
  int status = 0;
  (void)run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", 250}}, &status);
  REQUIRE(status == 200);
  httplib::Client client = run.client();
  const auto saved = client.Post(run.with_token("/api/save"), "", "application/json");
  REQUIRE(saved);
  CHECK(saved->status == 200);
  CHECK(test::slurp_file(victim) == "precious\n");
  CHECK(!std::filesystem::is_symlink(file));
  CHECK(test::slurp_file(file).find("250 N/m") != std::string::npos);
  struct stat status_of {};
  REQUIRE(::stat(file.c_str(), &status_of) == 0);
  CHECK((status_of.st_mode & 07777) == 0640);
  // Nothing else is left in the folder: the file, the victim and the four links.
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder.dir)) ++entries;
  CHECK(entries == 6);
}

}  // TEST_SUITE("threaded")

}  // namespace hapscene
