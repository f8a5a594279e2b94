// Every physical number of an environment has a finite range (docs/reference/
// environments.md): an absurd value is refused at load with the file and the JSON pointer, and the
// ends of each range load.
#include <doctest/doctest.h>

#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::load_error;

namespace {

// The load error of one effect.
std::string effect_error(const std::string& effect) { return load_error(R"({"effects": [)" + effect + "]}"); }

}  // namespace

TEST_CASE("value ranges: effect parameters beyond their range are refused, naming the key") {
  CHECK(effect_error(R"({"type": "spring", "stiffness": 1e308})") ==
        "test.json: /effects/0/stiffness: must be in [0, 10000000] N/m, got 1e+308 N/m");
  CHECK(effect_error(R"({"type": "spring", "stiffness": "1e300 kN/m"})") ==
        "test.json: /effects/0/stiffness: must be in [0, 10000000] N/m, got 1e+303 N/m");
  CHECK(effect_error(R"({"type": "spring", "stiffness": 100, "center": "2000 m"})") ==
        "test.json: /effects/0/center: must be in [-1000, 1000] m, got 2000 m");
  CHECK(effect_error(R"({"type": "wall", "position": -1e300, "stiffness": 500, "solid": "above"})") ==
        "test.json: /effects/0/position: must be in [-1000, 1000] m, got -1e+300 m");
  CHECK(effect_error(R"({"type": "wall", "position": 0.01, "stiffness": 1.1e7, "solid": "above"})") ==
        "test.json: /effects/0/stiffness: must be in [0, 10000000] N/m, got 11000000 N/m");
  CHECK(effect_error(R"({"type": "damper", "damping": 1e308})") ==
        "test.json: /effects/0/damping: must be in [0, 10000] N*s/m, got 1e+308 N*s/m");
  CHECK(effect_error(R"({"type": "texture", "width": 1e-300, "damping": 1})") ==
        "test.json: /effects/0/width: must be in [1e-06, 1000] m, got 1e-300 m");
  CHECK(effect_error(R"({"type": "texture", "width": 2000, "damping": 1})") ==
        "test.json: /effects/0/width: must be in [1e-06, 1000] m, got 2000 m");
  CHECK(effect_error(R"({"type": "texture", "width": 0.005, "damping": 20000})") ==
        "test.json: /effects/0/damping: must be in [0, 10000] N*s/m, got 20000 N*s/m");
  CHECK(effect_error(R"({"type": "texture", "width": 0.005, "spacing": 1e300, "damping": 1})") ==
        "test.json: /effects/0/spacing: must be in [0, 1000] m, got 1e+300 m");
  CHECK(effect_error(R"({"type": "texture", "width": 0.005, "offset": -1e300, "damping": 1})") ==
        "test.json: /effects/0/offset: must be in [-1000, 1000] m, got -1e+300 m");
  // Below a lower bound of 0, the words stay those of a sign error.
  CHECK(effect_error(R"({"type": "texture", "width": -0.005, "damping": 1})") ==
        "test.json: /effects/0/width: must be > 0, got -0.005 m");
  CHECK(effect_error(R"({"type": "spring", "stiffness": -5})") ==
        "test.json: /effects/0/stiffness: must be >= 0, got -5 N/m");
}

TEST_CASE("value ranges: the ends of each effect range load") {
  const Scene scene = test::scene_from(R"({"effects": [
    {"type": "spring", "stiffness": "10000 kN/m", "center": "-1000 m"},
    {"type": "wall", "position": 1000, "stiffness": 1e7, "solid": "below"},
    {"type": "damper", "damping": "10 N*s/mm"},
    {"type": "texture", "width": "1 um", "spacing": 1000, "offset": 1000, "damping": 1e4}]})");
  CHECK(std::get<Spring>(scene.effects[0]).stiffness_N_per_m == 1e7);
  CHECK(std::get<Wall>(scene.effects[1]).position_m == 1000.0);
  CHECK(std::get<Damper>(scene.effects[2]).damping_N_s_per_m == 1e4);
  CHECK(std::get<Texture>(scene.effects[3]).width_m == doctest::Approx(1e-6));
}

TEST_CASE("value ranges: safety, velocity, validate and script limits are bounded too") {
  CHECK(load_error(R"({"safety": {"soft_start": 1e300}, "effects": []})") ==
        "test.json: /safety/soft_start: must be in [0, 60] s, got 1e+300 s");
  CHECK(load_error(R"({"velocity": {"cutoff": "2000 kHz"}, "effects": []})") ==
        "test.json: /velocity/cutoff: must be in (0, 1000000] Hz, got 2000000 Hz");
  CHECK(load_error(R"({"validate": {"press_force": 1e300}, "effects": []})") ==
        "test.json: /validate/press_force: must be in (0, 1000] N, got 1e+300 N");
  CHECK(load_error(R"({"validate": {"release_from": -1e300}, "effects": []})") ==
        "test.json: /validate/release_from: must be in [-1000, 1000] m, got -1e+300 m");
  CHECK(load_error(R"({"validate": {"stiff_threshold": 1e300}, "effects": []})") ==
        "test.json: /validate/stiff_threshold: must be in (0, 10000000] N/m, got 1e+300 N/m");
  CHECK(load_error(R"({"validate": {"max_passivity_ratio": 1e300}, "effects": []})") ==
        "test.json: /validate/max_passivity_ratio: must be in (0, 1000000], got 1e+300");
  CHECK(load_error(R"({"validate": {"max_tick_compute": 3600}, "effects": []})") ==
        "test.json: /validate/max_tick_compute: must be in (0, 60] s, got 3600 s");
  const std::string script = R"({"type": "script", "source": "function force(s) return 0 end", "limits": )";
  CHECK(effect_error(script + R"({"wall_time_per_call": 1e300}})") ==
        "test.json: /effects/0/limits/wall_time_per_call: must be in [0, 60] s, got 1e+300 s");
  CHECK(effect_error(script + R"({"log_rate": "1000 kHz"}})") ==
        "test.json: /effects/0/limits/log_rate: must be in [0, 100000] Hz, got 1000000 Hz");
}

TEST_CASE("value ranges: an absurd value is exit 2 on the command line, with no output") {
  const test::ScratchFolder folder("value_ranges");
  const std::string env = folder.write("env.json", R"({"effects": [{"type": "spring", "stiffness": 1e308}]})").string();
  const auto probe = test::run_cli("probe " + env + " --x 0:0.01:0.01");
  CHECK(probe.exit_code == 2);
  CHECK(probe.out.empty());
  CHECK(probe.err == "error: " + env + ": /effects/0/stiffness: must be in [0, 10000000] N/m, got 1e+308 N/m\n");
}
