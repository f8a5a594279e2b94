// Hot reload: the loop takes a new scene at a tick boundary and cross-fades to it without
// a jolt; the reload thread compiles changed files off the loop and keeps the running
// version when the new one is broken.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/reload_watcher.hpp"
#include "engine/run/runner.hpp"
#include "tests/run/reload_support.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

std::unique_ptr<LoadedScene> loaded(const std::string& json) {
  auto next = std::make_unique<LoadedScene>();
  next->scene = test::scene_from(json);
  next->scripts = make_script_instances(next->scene);
  return next;
}

// Records forces, and offers a prepared scene at a chosen tick (no allocation).
class ReloadingTrace final : public TickObserver {
 public:
  ReloadingTrace(SceneExchange* exchange, std::unique_ptr<LoadedScene> later, std::uint64_t at_tick)
      : exchange_(exchange), later_(std::move(later)), at_tick_(at_tick) {
    x_m.reserve(4000);
    effects_N.reserve(4000);
    output_N.reserve(4000);
  }
  void on_tick(const TickState& s) noexcept override {
    x_m.push_back(s.x_m);
    effects_N.push_back(s.effects_force_N);
    output_N.push_back(s.output_N);
    if (s.tick == at_tick_ && later_ != nullptr) exchange_->offer(later_);
  }
  std::vector<double> x_m, effects_N, output_N;

 private:
  SceneExchange* exchange_;
  std::unique_ptr<LoadedScene> later_;
  std::uint64_t at_tick_;
};

}  // namespace

TEST_CASE("hot swap: a reloaded scene cross-fades in at a tick boundary, without a jolt") {
  const Scene first = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  SceneExchange exchange;
  // The second version pulls toward +20 mm (2 N more at the centre); the third is a damper.
  auto second = loaded(R"({"effects": [{"type": "spring", "stiffness": 100, "center": 0.02}]})");
  REQUIRE(exchange.offer(second));
  ReloadingTrace trace(&exchange, loaded(R"({"effects": [{"type": "damper", "damping": 1}]})"), 1500);

  SimulationConfig config;
  config.hand.motion = HandMotion::hold;  // a hand holding the handle at 0
  SimulatedHapkit device(first.device, config);
  RunOptions options{.duration_s = 3.0, .pacing = Pacing::simulated_time};
  set_reload_exchange<1>(&options, &exchange);
  const RunSummary summary = run_scene(first, device, options, &trace);

  CHECK(exchange.swaps() == 2);
  CHECK(summary.scene_name == "test");
  // The fade takes the new scene's soft-start time (0.5 s): force moves smoothly.
  double largest_step_N = 0.0;
  for (std::size_t i = 1; i < trace.output_N.size(); ++i) {
    largest_step_N = std::max(largest_step_N, std::abs(trace.output_N[i] - trace.output_N[i - 1]));
  }
  CHECK(largest_step_N < 0.02);
  // Half-way through the first fade, half of each; after it, only the second version.
  const double x_250 = trace.x_m[250];
  CHECK(trace.effects_N[250] == doctest::Approx(0.5 * (-100.0 * x_250) + 0.5 * (-100.0 * (x_250 - 0.02))).epsilon(0.01));
  CHECK(trace.effects_N[1000] == doctest::Approx(-100.0 * (trace.x_m[1000] - 0.02)));
  // The second version was let go of after the third faded in, and handed back.
  CHECK(exchange.take_retired() != nullptr);
}

TEST_CASE("hot swap: without an exchange nothing changes") {
  const Scene scene = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  TickState state = make_tick_state(scene);
  HotSwap swap(scene, nullptr, &state);
  CHECK(swap.before_tick(&state) == nullptr);
  CHECK(&swap.scene() == &scene);
}

TEST_CASE("reload watcher: a changed file is compiled off the loop and offered, a broken one is not" * doctest::test_suite("threaded")) {
  const auto dir = std::filesystem::temp_directory_path() / ("hapscene_reload_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto env = dir / "env.json";
  const auto script = dir / "push.lua";
  const auto write = [](const std::filesystem::path& path, const std::string& text) {
    const bool existed = std::filesystem::exists(path);
    const auto before = existed ? std::filesystem::last_write_time(path) : std::filesystem::file_time_type{};
    std::ofstream(path) << text;
    // File times can be coarser than a test's edits: move it forward explicitly.
    if (existed) std::filesystem::last_write_time(path, before + std::chrono::seconds(1));
  };
  write(script, "params = {f = 1.0}\nfunction force(s) return params.f end\n");
  write(env, R"({"effects": [{"type": "script", "file": "push.lua"}]})");

  const Scene running = load_environment_file(env.string());
  SceneExchange exchange;
  std::vector<std::string> reports;
  ReloadWatcher watcher(env.string(), running, &exchange,
                        [&](const std::string& message) { reports.push_back(message); },
                        test::manual_polling());

  // Nothing changed: nothing offered.
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);

  // The script file changes: its new version is offered, compiled and instantiated.
  write(script, "params = {f = 2.0}\nfunction force(s) return params.f end\n");
  watcher.poll();
  std::unique_ptr<LoadedScene> offered(exchange.take_offer());
  REQUIRE(offered != nullptr);
  REQUIRE(offered->scripts.size() == 1);
  CHECK(offered->scripts[0]->force_N(ScriptInput{}) == 2.0);
  REQUIRE(reports.size() == 1);
  CHECK(reports[0] == "reloaded " + env.string() + ": cross-fading to the new version");

  // A broken version is reported; the running one stays.
  write(script, "params = {f = 3.0}\nfunction force(s) return params.f +\n");
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  REQUIRE(reports.size() == 2);
  CHECK(reports[1].starts_with("reload failed, keeping the running version: " + env.string() + ": /effects/0/file: " +
                               script.string() + ":3:"));

  // The rate cannot change during a run.
  write(script, "params = {f = 2.0}\nfunction force(s) return params.f end\n");
  write(env, R"({"rate_hz": 2000, "effects": [{"type": "script", "file": "push.lua"}]})");
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  CHECK(reports.back() == "reload refused, keeping the running version: " + env.string() +
                              ": rate_hz cannot change during a run (1000 -> 2000)");
  std::filesystem::remove_all(dir);
}
