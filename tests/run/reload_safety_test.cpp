// Hot reload cannot loosen safety or hang the run: a reload that changes the device
// profile's content (even under the same name) or loosens a limit is refused, and a load
// that never ends is abandoned without holding up the run.
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "engine/run/reload_guard.hpp"
#include "engine/run/reload_watcher.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/run/reload_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// The shipped profile with its force and slew limits replaced (the name stays "hapkit3").
std::string hapkit3_with(const std::string& max_force, const std::string& slew_limit) {
  std::string text = test::slurp_file(test::source_path("environments/devices/hapkit3.json"));
  text = std::regex_replace(text, std::regex(R"("max_force": "6 N")"), "\"max_force\": \"" + max_force + "\"");
  text = std::regex_replace(text, std::regex(R"("slew_limit": "4 N/ms")"), "\"slew_limit\": \"" + slew_limit + "\"");
  return text;
}

}  // namespace

TEST_CASE("reload guard: each loosened limit, the rate and any profile change are named") {
  const Scene running = test::scene_from(
      R"({"safety": {"max_force": "3 N", "slew_limit": "2 N/ms", "workspace": ["-40 mm", "40 mm"],
          "soft_start": "1 s"}, "effects": []})");
  CHECK(reload_refusal(running, running) == "");
  // Tightening is allowed; so is changing the effects.
  CHECK(reload_refusal(running, test::scene_from(
      R"({"safety": {"max_force": "2 N", "slew_limit": "1 N/ms", "workspace": ["-30 mm", "30 mm"],
          "soft_start": "2 s"}, "effects": [{"type": "spring", "stiffness": 100}]})")) == "");
  CHECK(reload_refusal(running, test::scene_from(
      R"({"safety": {"max_force": "4 N", "slew_limit": "2 N/ms", "workspace": ["-40 mm", "40 mm"],
          "soft_start": "1 s"}, "effects": []})")) ==
        "a reload cannot loosen a safety limit (max_force_N 3 -> 4); restart the run to loosen one");
  const std::string all = reload_refusal(running, test::scene_from(R"({"effects": []})"));
  for (const char* named : {"max_force_N 3 -> 6", "slew_limit_N_per_s 2000 -> 4000", "workspace_min_m -0.04 -> -0.05",
                            "workspace_max_m 0.04 -> 0.045", "soft_start_s 1 -> 0.5"}) {
    CHECK_MESSAGE(all.find(named) != std::string::npos, all);
  }
  Scene hotter = running;
  hotter.safety.soft_start_threshold_N = 2.0;
  CHECK(reload_refusal(running, hotter).find("soft_start_threshold_N 0.5 -> 2") != std::string::npos);
  Scene faster = running;
  faster.rate_hz = 2000;
  CHECK(reload_refusal(running, faster).starts_with("rate_hz cannot change during a run (1000 -> 2000)"));
  // The profile's content, whatever its name: a lower limit there is refused too.
  Scene other_device = running;
  other_device.device.plant.mass_kg = 0.05;
  other_device.device.limits.max_force_N = 5.0;
  CHECK(reload_refusal(running, other_device) ==
        "the device cannot change during a run (profile limits.max_force_N 6 -> 5, plant.mass_kg 0.04 -> 0.05)");
}

TEST_CASE("reload watcher: a same-named profile file with looser limits is refused, the limits stay" * doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("reload_profile");
  scratch.write("a/hapkit3.json", hapkit3_with("6 N", "4 N/ms"));
  scratch.write("b/hapkit3.json", hapkit3_with("60 N", "8 N/ms"));
  const auto env = scratch.write("env.json", R"({"device": "a/hapkit3.json", "effects": [{"type": "spring", "stiffness": 1000}]})");
  const Scene running = load_environment_file(env.string());
  SceneExchange exchange;
  test::Reports reports;
  ReloadWatcher watcher(env.string(), running, &exchange, reports.sink(), test::manual_polling());

  // The environment now points at the other file, whose profile has the same name.
  scratch.write("env.json", R"({"device": "b/hapkit3.json", "effects": [{"type": "spring", "stiffness": 1000}]})");
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  // Both are named: the profile changed, and so would the limits in force.
  CHECK(reports.last() == "reload refused, keeping the running version: " + env.string() +
                              ": the device cannot change during a run (profile limits.max_force_N 6 -> 60, "
                              "limits.slew_limit_N_per_s 4000 -> 8000); a reload cannot loosen a safety limit "
                              "(max_force_N 6 -> 60, slew_limit_N_per_s 4000 -> 8000); restart the run to loosen one");

  // The same file edited in place is the same attack.
  scratch.write("env.json", R"({"device": "a/hapkit3.json", "effects": [{"type": "spring", "stiffness": 1000}]})");
  scratch.write("a/hapkit3.json", hapkit3_with("60 N", "4 N/ms"));
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  CHECK(reports.last().find("limits.max_force_N 6 -> 60") != std::string::npos);

  // Tightening through the environment is taken; loosening back afterwards is not.
  scratch.write("a/hapkit3.json", hapkit3_with("6 N", "4 N/ms"));
  scratch.write("env.json", R"({"device": "a/hapkit3.json", "safety": {"max_force": "2 N"},
                                "effects": [{"type": "spring", "stiffness": 1000}]})");
  watcher.poll();
  std::unique_ptr<LoadedScene> tighter(exchange.take_offer());
  REQUIRE(tighter != nullptr);
  CHECK(tighter->scene.safety.max_force_N == 2.0);
  scratch.write("env.json", R"({"device": "a/hapkit3.json", "effects": [{"type": "spring", "stiffness": 1000}]})");
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  CHECK(reports.last() == "reload refused, keeping the running version: " + env.string() +
                              ": a reload cannot loosen a safety limit (max_force_N 2 -> 6); restart the run to loosen one");
}

TEST_CASE("reload watcher: a load that never ends is abandoned, destroying the watcher does not wait for it" * doctest::test_suite("threaded")) {
  const Scene running = test::scene_from(R"({"effects": []})");
  test::ScratchFolder scratch("reload_hang");
  const auto env = scratch.write("env.json", R"({"effects": []})");
  // A load that blocks until the test lets it go.
  struct Gate {
    std::mutex mutex;
    std::condition_variable open_cv;
    bool open{false};
    int entered{0};
  };
  auto gate = std::make_shared<Gate>();
  ReloadWatcherOptions options;
  options.poll_period_s = 0.01;
  options.compile_timeout_s = 0.2;
  options.load = [gate](const std::string&) -> std::unique_ptr<LoadedScene> {
    std::unique_lock lock(gate->mutex);
    ++gate->entered;
    gate->open_cv.wait(lock, [&] { return gate->open; });
    throw InputError("let go");
  };
  SceneExchange exchange;
  test::Reports reports;
  {
    auto watcher = std::make_unique<ReloadWatcher>(env.string(), running, &exchange, reports.sink(), options);
    scratch.write("env.json", R"({"effects": [{"type": "damper", "damping": 1}]})");
    // Within the timeout plus a few polls the stuck load is reported and abandoned.
    for (int i = 0; i < 300 && reports.count() == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    REQUIRE(reports.count() == 1);
    CHECK(reports.last() == "reload of " + env.string() +
                                " abandoned, keeping the running version: it did not finish within 0.2 s");
    // A later edit starts a new load (the watcher is not stuck); the watcher is then
    // destroyed while that one hangs too, and returns at once.
    scratch.write("env.json", R"({"effects": [{"type": "damper", "damping": 2}]})");
    for (int i = 0; i < 300; ++i) {
      {
        std::lock_guard lock(gate->mutex);
        if (gate->entered == 2) break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    const auto before = std::chrono::steady_clock::now();
    watcher.reset();
    CHECK(std::chrono::steady_clock::now() - before < std::chrono::milliseconds(500));
  }
  CHECK(reports.count() >= 2);
  CHECK(reports.last().find("abandoned") != std::string::npos);
  CHECK(ReloadWatcher::abandoned_loads() >= 2);
  // Let the abandoned loads end (they hold only their own data).
  {
    std::lock_guard lock(gate->mutex);
    gate->open = true;
  }
  gate->open_cv.notify_all();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
}
