// The live status drains script log messages from its own thread while hot reload swaps
// the script instances on the loop and destroys replaced ones on the reload thread. Run
// under ThreadSanitizer (see docs/explanation/testing.md) this is the reproducer of the race where
// the status thread read the script list the loop swapped; here it also checks that no
// version's messages are lost.
#include <doctest/doctest.h>

#include <atomic>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/live_status.hpp"
#include "engine/run/observer_list.hpp"
#include "engine/run/runner.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// A scene with two scripts that log their version every call (the rate limit keeps it
// to a few per second of run time).
std::string logging_scene(int version) {
  const std::string source = "function force(s) log('v" + std::to_string(version) + "') return 0 end";
  return R"({"effects": [{"type": "script", "source": ")" + source + R"("},
                          {"type": "script", "source": ")" + source + R"("}]})";
}

// Offers the prepared versions one after another, each as soon as the slot is free
// and at least `spacing` ticks after the last (no allocation on the loop).
class Offerer final : public TickObserver {
 public:
  Offerer(SceneExchange* exchange, std::vector<std::unique_ptr<LoadedScene>> versions, std::uint64_t spacing)
      : exchange_(exchange), versions_(std::move(versions)), spacing_(spacing) {}
  void on_tick(const TickState& s) noexcept override {
    if (next_ >= versions_.size() || s.tick < last_offer_tick_ + spacing_) return;
    if (exchange_->offer(versions_[next_])) {
      ++next_;
      last_offer_tick_ = s.tick;
    }
  }

 private:
  SceneExchange* exchange_;
  std::vector<std::unique_ptr<LoadedScene>> versions_;
  std::uint64_t spacing_;
  std::size_t next_{0};
  std::uint64_t last_offer_tick_{0};
};

}  // namespace

TEST_CASE("live status: draining logs while reloads swap and destroy script instances is race-free and loses nothing" * doctest::test_suite("threaded")) {
  const Scene first = test::scene_from(logging_scene(0));
  constexpr int kVersions = 8;
  std::vector<std::unique_ptr<LoadedScene>> versions;
  for (int v = 1; v <= kVersions; ++v) {
    auto next = std::make_unique<LoadedScene>();
    next->scene = test::scene_from(logging_scene(v));
    next->scripts = make_script_instances(next->scene);
    versions.push_back(std::move(next));
  }
  SceneExchange exchange;
  LiveStatus status;
  Offerer offerer(&exchange, std::move(versions), 600);
  ObserverList observers;
  observers.add(&status);
  observers.add(&offerer);

  // The status thread and the reload thread's part, running while the loop runs.
  std::atomic<bool> done{false};
  std::vector<std::string> lines;
  std::thread reader([&] {
    while (!done.load()) {
      status.drain_log(&lines);
      std::this_thread::yield();
    }
  });
  std::thread reaper([&] {
    while (!done.load()) {
      if (std::unique_ptr<LoadedScene> retired = exchange.take_retired()) status.drain_retired(*retired);
      std::this_thread::yield();
    }
  });

  SimulationConfig config;
  config.hand.motion = HandMotion::hold;
  SimulatedHapkit device(first.device, config);
  RunOptions options{.duration_s = 30.0, .pacing = Pacing::simulated_time};
  set_reload_exchange<1>(&options, &exchange);
  const RunSummary summary = run_scene(first, device, options, &observers);
  done.store(true);
  reader.join();
  reaper.join();
  if (std::unique_ptr<LoadedScene> retired = exchange.take_retired()) status.drain_retired(*retired);
  status.drain_log(&lines);

  CHECK(summary.ticks == 30000);
  CHECK(exchange.swaps() >= 2);
  // Messages of the first version, of every version taken, and none dropped silently.
  std::set<std::string> seen;
  for (const std::string& line : lines) {
    const std::size_t at = line.find(": v");
    if (at != std::string::npos) seen.insert(line.substr(at + 2, line.find(' ', at + 2) - at - 2));
  }
  CHECK(seen.count("v0") == 1);
  CHECK(seen.size() == exchange.swaps() + 1);
  MESSAGE("reloads taken: " << exchange.swaps() << ", log lines drained: " << lines.size());
}
