// A run ends when its last tick does: destroying a reload watcher wakes its thread from the
// wait between polls instead of letting it sleep out the period. The poll period here is a
// minute, so a watcher that sleeps it out would take 60 s to stop; the bound (20 s) is far
// from both, so the test does not depend on the machine's speed.
#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "engine/load/environment.hpp"
#include "engine/run/reload_watcher.hpp"
#include "tests/run/reload_support.hpp"

using namespace hapscene;

TEST_CASE("a reload watcher stops at once when destroyed, whatever its poll period") {
  const auto dir = std::filesystem::temp_directory_path() / "hapscene_watcher_exit_test";
  std::filesystem::create_directories(dir);
  const auto env = dir / "env.json";
  std::ofstream(env) << R"({"effects": [{"type": "spring", "stiffness": "100 N/m"}]})";
  const Scene running = load_environment_file(env.string());
  SceneExchange exchange;
  test::Reports reports;
  ReloadWatcherOptions options;
  options.poll_period_s = 60.0;

  auto watcher = std::make_unique<ReloadWatcher>(env.string(), running, &exchange, reports.sink(), options);
  const auto begin = std::chrono::steady_clock::now();
  watcher.reset();
  const std::chrono::duration<double> stop_s = std::chrono::steady_clock::now() - begin;
  CHECK(stop_s.count() < 20.0);
  CHECK(reports.count() == 0);
  std::filesystem::remove_all(dir);
}
