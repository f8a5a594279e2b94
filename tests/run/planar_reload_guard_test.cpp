// Hot reload of a 2-DOF scene, the reload thread's side: the guard names every change of
// the planar profile and every loosened limit (the workspace per axis), and the watcher
// offers a changed planar file, keeps a broken one out, and refuses a file that now makes
// a 1-DOF scene.
#include <doctest/doctest.h>

#include <memory>
#include <mutex>
#include <regex>
#include <string>
#include <vector>

#include "engine/base/object_reader.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/reload_guard.hpp"
#include "engine/run/reload_watcher.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/run/reload_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

PlanarScene planar(const std::string& text) { return load_planar_environment_text(text, "t.json", HAPSCENE_SOURCE_DIR); }

const char* kSpring = R"("effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["-16 mm", "140 mm"]}])";

}  // namespace

TEST_CASE("planar reload guard: a loosened limit is named per axis, the profile's content and name are compared") {
  const PlanarScene running = planar(std::string(R"({"device": "haplink", "safety": {"max_force": "1 N",
      "workspace": {"min": ["-50 mm", "100 mm"], "max": ["20 mm", "160 mm"]}}, )") + kSpring + "}");
  CHECK(reload_refusal(running, running) == "");
  // Tighter on both axes and in force: taken.
  CHECK(reload_refusal(running, planar(std::string(R"({"device": "haplink", "safety": {"max_force": "0.5 N",
      "workspace": {"min": ["-40 mm", "110 mm"], "max": ["10 mm", "150 mm"]}}, )") + kSpring + "}")) == "");
  // Back to the profile's limits: every loosened bound is named, with its axis.
  const std::string loosened = reload_refusal(running, planar(std::string(R"({"device": "haplink", )") + kSpring + "}"));
  CHECK(loosened == "a reload cannot loosen a safety limit (max_force_N 1 -> 2, workspace_min_m.x -0.05 -> -0.07, "
                    "workspace_max_m.x 0.02 -> 0.04, workspace_min_m.y 0.1 -> 0.09, workspace_max_m.y 0.16 -> 0.165); "
                    "restart the run to loosen one");
  // Another device.
  const std::string other = reload_refusal(running, planar(std::string(R"({"device": "haply2diy_v3", )") + kSpring + "}"));
  CHECK(other.starts_with("the device cannot change during a run (profile name \"haplink\" -> \"haply2diy_v3\", "));
  CHECK(other.find("linkage.family (0 serial_2r, 1 five_bar) 0 -> 1") != std::string::npos);
  // The same name, another number anywhere in the profile.
  PlanarScene changed = running;
  changed.device.linkage.serial.link_a_m = 0.09;
  changed.device.joints[1].drive.duty_per_N_m = 70.0;
  changed.device.plant.links[0].mass_kg = 0.5;
  CHECK(reload_refusal(running, changed) ==
        "the device cannot change during a run (profile linkage.link_a_m 0.087 -> 0.09, joints[2].drive.duty_per_N_m "
        "65.13 -> 70, plant.links[1].mass_kg " +
            format_number(running.device.plant.links[0].mass_kg) + " -> 0.5)");
}

TEST_CASE("planar reload watcher: a changed file is offered, a broken one is reported and kept out, a 1-DOF one refused" *
          doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("planar_reload_watch");
  const auto env = scratch.write("env.json", std::string(R"({"device": "haplink", )") + kSpring + "}");
  const PlanarScene running = load_planar_environment_file(env.string());
  SceneExchangeOf<2> exchange;
  test::Reports reports;
  ReloadWatcherOptionsOf<2> manual;
  manual.poll_period_s = 0.0;  // the test polls
  ReloadWatcherOf<2> watcher(env.string(), running, &exchange, reports.sink(), manual);

  scratch.write("env.json", R"({"device": "haplink", "effects": [{"type": "spring", "stiffness": "300 N/m", "center": ["-16 mm", "140 mm"]}]})");
  watcher.poll();
  std::unique_ptr<LoadedSceneOf<2>> next(exchange.take_offer());
  REQUIRE(next != nullptr);
  CHECK(reports.last() == "reloaded " + env.string() + ": cross-fading to the new version");
  CHECK(next->scene.effects.size() == 1);

  scratch.write("env.json", R"({"device": "haplink", "effects": [{"type": "spring", "stiffness": "300 N/m", "center": "1 mm"}]})");
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  CHECK(reports.last().starts_with("reload failed, keeping the running version: " + env.string() + ": /effects/0/center: "));

  scratch.write("env.json", R"({"effects": [{"type": "spring", "stiffness": "300 N/m"}]})");
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  CHECK(reports.last() == "reload refused, keeping the running version: " + env.string() +
                              ": the device cannot change during a run (the file now makes a 1-DOF scene; this run's "
                              "is 2-DOF (planar))");
}

TEST_CASE("planar reload watcher: an edit of a 2-D script the scene uses is a new version too" *
          doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("planar_reload_script");
  scratch.write("field.lua", "function force(s) return 0, 0 end\n");
  const auto env = scratch.write("env.json", R"({"device": "haplink", "effects": [{"type": "script", "file": "field.lua"}]})");
  const PlanarScene running = load_planar_environment_file(env.string());
  SceneExchangeOf<2> exchange;
  test::Reports reports;
  ReloadWatcherOptionsOf<2> manual;
  manual.poll_period_s = 0.0;  // the test polls
  ReloadWatcherOf<2> watcher(env.string(), running, &exchange, reports.sink(), manual);

  watcher.poll();  // nothing changed
  CHECK(exchange.take_offer() == nullptr);
  scratch.write("field.lua", "function force(s) return -100 * s.x, -100 * s.y end\n");
  watcher.poll();
  std::unique_ptr<LoadedSceneOf<2>> next(exchange.take_offer());
  REQUIRE(next != nullptr);
  REQUIRE(next->scripts.size() == 1);
  PlanarScriptInput at;
  at.x_m = Vec2{{0.01, 0.02}};
  const Vec2 force = next->scripts[0]->force_N(at);
  CHECK(force[0] == doctest::Approx(-1.0));
  CHECK(force[1] == doctest::Approx(-2.0));
  // A script of the other dimension is a located load error; the running version stays.
  scratch.write("field.lua", "function force(s) return -100 * s.x end\n");
  watcher.poll();
  CHECK(exchange.take_offer() == nullptr);
  CHECK(reports.last().starts_with("reload failed, keeping the running version: "));
}
