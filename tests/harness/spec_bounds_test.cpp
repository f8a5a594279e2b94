// What test specs and validate evaluate, they evaluate in bounded time and within the
// command line's ranges: a script that faults only in motion or after some time fails a
// spec without scenarios; spec options and points outside the ranges validate and probe
// accept are refused with the spec file and JSON pointer; a script too slow for the loop
// stops validate and test early with a failed "pace" check.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <string>

#include "engine/harness/figures.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/option_ranges.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/planar_open_loop.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/harness/test_spec.hpp"
#include "engine/harness/validate.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// A spec over `script` with one force expectation at rest, nothing that runs.
SpecResult spec_over_script(const char* tag, const std::string& script) {
  const test::ScratchFolder folder(tag);
  folder.write("s.lua", script);
  const auto spec = folder.write("s.test.json", R"({"environment": "s.lua", "forces": [{"x": "0 mm", "force": "0 N"}]})");
  return run_test_spec(spec.string());
}

bool has_fault_outcome(const SpecResult& result, const std::string& text) {
  for (const SpecOutcome& o : result.outcomes) {
    if (!o.pass && o.what == "/environment" && o.message.find(text) != std::string::npos) return true;
  }
  return false;
}

std::string spec_error(const char* tag, const std::string& spec_text) {
  const test::ScratchFolder folder(tag);
  folder.write("s.lua", "needs = {velocity = false, time = false}\nfunction force(s) return -100 * s.x end\n");
  const auto spec = folder.write("s.test.json", spec_text);
  const std::string message = test::input_error_of([&] { run_test_spec(spec.string()); });
  // Relative to the folder, so the expectations read plainly.
  const std::string prefix = spec.string() + ": ";
  return message.starts_with(prefix) ? "s.test.json: " + message.substr(prefix.size()) : message;
}

}  // namespace

TEST_CASE("spec: a script that faults only when moving fails a spec without scenarios") {
  const SpecResult result = spec_over_script("motion_fault",
                                             "function force(s)\n"
                                             "  if s.v > 0.05 then return k end\n"
                                             "  return 0\n"
                                             "end\n");
  CHECK_FALSE(result.pass);
  CHECK(has_fault_outcome(result, ":2: undefined global 'k' (first at x "));
  CHECK(has_fault_outcome(result, "v 0.1 m/s, t 0 s)"));
  // Moving downwards only.
  CHECK_FALSE(spec_over_script("motion_fault_down",
                               "function force(s)\n  if s.v < -1 then return k end\n  return 0\nend\n")
                  .pass);
}

TEST_CASE("spec: a script that faults only after some time fails a spec without scenarios") {
  const SpecResult result = spec_over_script("time_fault",
                                             "needs = {velocity = false}\n"
                                             "function force(s)\n"
                                             "  if s.t > 1 then return k end\n"
                                             "  return 0\n"
                                             "end\n");
  CHECK_FALSE(result.pass);
  CHECK(has_fault_outcome(result, ":3: undefined global 'k'"));
  CHECK(has_fault_outcome(result, "t 3 s)"));
}

TEST_CASE("spec: scripts that do not fault in motion still pass, and a spec expecting the fault passes") {
  CHECK(spec_over_script("motion_ok", "function force(s) return -100 * s.x - 2 * s.v + 0 * s.t end\n").pass);
  // The scan does not invent faults from state: a virtual mass swept by one instance.
  CHECK(run_test_spec(test::source_path("scripts/mass_spring.test.json")).pass);
  CHECK(run_test_spec(test::source_path("scripts/vibration.test.json")).pass);
}

TEST_CASE("spec: options and forces outside the command line's ranges are refused with the place") {
  CHECK(spec_error("range_noise", R"({"environment": "s.lua", "options": {"noise": -3}})") ==
        "s.test.json: /options/noise: must be in [0, 1000] counts, got -3 counts");
  CHECK(spec_error("range_noise_big", R"({"environment": "s.lua", "options": {"noise": 1e6}})") ==
        "s.test.json: /options/noise: must be in [0, 1000] counts, got 1000000 counts");
  CHECK(spec_error("range_k", R"({"environment": "s.lua", "options": {"hand_stiffness": "1e30 N/m"}})") ==
        "s.test.json: /options/hand_stiffness: must be in (0, 1000000] N/m, got 1e+30 N/m");
  CHECK(spec_error("range_k0", R"({"environment": "s.lua", "options": {"hand_stiffness": 0}})") ==
        "s.test.json: /options/hand_stiffness: must be in (0, 1000000] N/m, got 0 N/m");
  CHECK(spec_error("range_b", R"({"environment": "s.lua", "options": {"hand_damping": "1e5 N*s/m"}})")
            .starts_with("s.test.json: /options/hand_damping: must be in [0, 10000] "));
  CHECK(spec_error("range_m", R"({"environment": "s.lua", "options": {"hand_mass": "50 kg"}})") ==
        "s.test.json: /options/hand_mass: must be in [0, 10] kg, got 50 kg");
  CHECK(spec_error("range_start", R"({"environment": "s.lua", "options": {"start": "5 m"}})") ==
        "s.test.json: /options/start: must be in [-1, 1] m, got 5 m");
  CHECK(spec_error("range_v", R"({"environment": "s.lua", "forces": [{"x": 0, "v": 1e300, "force": 0}]})") ==
        "s.test.json: /forces/0/v: must be in [-1000, 1000] m/s, got 1e+300 m/s");
  CHECK(spec_error("range_x", R"({"environment": "s.lua", "forces": [{"x": "1e9 m", "force": 0}]})") ==
        "s.test.json: /forces/0/x: must be in [-1000, 1000] m, got 1000000000 m");
  // The same numbers as the command line: one definition.
  CHECK(value_range::noise.max == 1000.0);
  CHECK(describe_range(value_range::hand_stiffness) == "(0, 1000000] N/m");
}

TEST_CASE("spec: a start outside the device's home period names the spec and /options/start") {
  const std::string message =
      spec_error("start_home", R"({"environment": "s.lua", "options": {"start": "0.5 m"}, "passes_validate": true})");
  CHECK(message.starts_with("s.test.json: /options/start: start position 0.5 m is outside the sensor's home period ["));
  // Also when nothing runs: the value is wrong for this environment either way.
  CHECK(spec_error("start_home_norun", R"({"environment": "s.lua", "options": {"start": "0.5 m"}})")
            .starts_with("s.test.json: /options/start: start position 0.5 m"));
  // A start inside the home period is accepted.
  CHECK(spec_error("start_ok", R"({"environment": "s.lua", "options": {"start": "2 mm"}})") == "(no error)");
}

namespace {

// About 20-40 ms of CPU per call, within a raised instruction budget (backstop 10 s).
const char* kSlowScript =
    "needs = {velocity = false, time = false}\n"
    "function force(s)\n"
    "  local a = 0\n"
    "  for i = 1, 3000000 do a = a + i end\n"
    "  return 0\n"
    "end\n";
// Fast for the first 0.3 s of a run, then as slow until 0.7 s: between the run times
// the open-loop scans look at (0.25 s, then 0.7071 s), which would find it too slow
// before any run (ScanPace).
const char* kSlowLaterScript =
    "needs = {velocity = false}\n"
    "function force(s)\n"
    "  local a = 0\n"
    "  if s.t > 0.3 and s.t < 0.7 then for i = 1, 3000000 do a = a + i end end\n"
    "  return 0\n"
    "end\n";

// Writes slow.lua and slow.json (its script with a raised instruction budget) into `folder`.
std::string slow_environment(const test::ScratchFolder& folder, const std::string& script) {
  folder.write("slow.lua", script);
  return folder
      .write("slow.json",
             R"({"name": "slow", "effects": [{"type": "script", "file": "slow.lua", "limits": {"instructions_per_call": 100000000}}]})")
      .string();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("pace: a script too slow for the loop fails validate at once, with the numbers") {
  const test::ScratchFolder folder("slow_validate");
  const Scene scene = load_environment_file(slow_environment(folder, kSlowScript));
  const auto start = std::chrono::steady_clock::now();
  const ValidationReport report = validate_scene(scene, {}, {});
  CHECK(seconds_since(start) < 10.0);  // without the check: hours
  CHECK_FALSE(report.pass);
  CHECK(report.scenarios.empty());
  REQUIRE(report.scene_checks.size() == 1);
  const CheckResult& pace = report.scene_checks[0];
  CHECK(pace.name == "pace");
  CHECK_FALSE(pace.pass);
  CHECK(pace.value > scene.period_s);
  CHECK(pace.detail.starts_with("too slow for the 1000 Hz loop: force() took "));
  CHECK(pace.detail.find(" ms of CPU time per call on average over the first ") != std::string::npos);
  CHECK(pace.detail.ends_with(" calls (the tick period is 1 ms)"));
}

TEST_CASE("pace: a script that becomes too slow during a run stops that run with a failed pace check") {
  const test::ScratchFolder folder("slow_later");
  const Scene scene = load_environment_file(slow_environment(folder, kSlowLaterScript));
  const auto start = std::chrono::steady_clock::now();
  const ValidationReport report = validate_scene(scene, {ScenarioKind::free}, {});
  CHECK(seconds_since(start) < 10.0);
  CHECK_FALSE(report.pass);
  REQUIRE(report.scenarios.size() == 1);
  const ScenarioResult& free = report.scenarios[0];
  REQUIRE(free.checks.size() == 1);
  CHECK(free.checks[0].name == "pace");
  CHECK(free.checks[0].detail.find("per tick on average over the ") != std::string::npos);
  // The run stopped soon after the script became slow (at 0.3 s, of a 2 s scenario).
  CHECK(free.records.size() < 700);
}

TEST_CASE("pace: a test spec over a slow script fails at once with the message") {
  const test::ScratchFolder folder("slow_spec");
  slow_environment(folder, kSlowScript);
  const auto spec = folder.write("slow.test.json", R"({"environment": "slow.json", "zero_outside": ["-1 mm", "1 mm"]})");
  const auto start = std::chrono::steady_clock::now();
  const SpecResult result = run_test_spec(spec.string());
  CHECK(seconds_since(start) < 10.0);
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 1);
  CHECK(result.outcomes[0].what == "/environment");
  CHECK(result.outcomes[0].message.starts_with("too slow for the 1000 Hz loop: force() took "));
}

TEST_CASE("pace: ordinary scripts keep up with a wide margin") {
  for (const char* name : {"scripts/pong.lua", "scripts/mass_spring.lua", "scripts/texture.lua"}) {
    CAPTURE(name);
    const Scene scene = load_environment_file(test::source_path(name));
    CHECK_FALSE(check_script_pace(scene).has_value());
  }
}

TEST_CASE("pace: the force field and the force-displacement curve of a slow script are not probed") {
  const test::ScratchFolder folder("slow_field");
  const Scene scene = load_environment_file(slow_environment(folder, kSlowScript));
  const auto start = std::chrono::steady_clock::now();
  const ForceField field = probe_force_field(scene, ValidateThresholds{}.stiff_threshold_N_per_m);
  CHECK(field.too_slow.starts_with("too slow for the 1000 Hz loop: "));
  CHECK(field.force_N.empty());
  const PlotPanel panel = force_displacement_panel(scene);
  CHECK(panel.series.empty());
  CHECK(panel.title.find(": not drawn, too slow for the 1000 Hz loop") != std::string::npos);
  CHECK(seconds_since(start) < 10.0);  // without the check: thousands of 30 ms calls
}

namespace {

// A script that keeps the loop's pace but is too slow for the checks' scans: its call
// takes about 0.35 ms of CPU (under the 1 ms period, over the tenth of it the scans allow a
// call, as they call it thousands of times). The loop's length is measured on this build
// and machine (a sanitizer build runs Lua three times slower), and the environment raises
// the instruction budget so that a slow machine's count fits.
std::string busy_script(long iterations, int axes) {
  return "needs = {velocity = false, time = false}\n"
         "function force(s)\n"
         "  local a = 0\n"
         "  for i = 1, " + std::to_string(iterations) + " do a = a + i end\n" +
         (axes == 1 ? std::string("  return -100 * s.x\n") : std::string("  return -100 * (s.x + 0.015), -100 * (s.y - 0.13)\n")) +
         "end\n";
}

double thread_cpu_s() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

const char* kBusyLimits = R"("limits": {"instructions_per_call": 50000000})";

// The loop length that takes about 0.35 ms a call here.
long busy_iterations(const test::ScratchFolder& folder) {
  constexpr long kTrial = 20000;
  folder.write("trial.lua", busy_script(kTrial, 1));
  const std::string environment = folder.write("trial.json", std::string(R"({"name": "trial", "effects": [{"type": "script", "file": "trial.lua", )") +
                                                                 kBusyLimits + "}]}").string();
  const Scene scene = load_environment_file(environment);
  ScriptList instances = make_script_instances(scene);
  EffectInput at_rest;
  at_rest.x_m = 0.01;
  at_rest.dt_s = scene.period_s;
  double best_s = 1e9;
  for (int round = 0; round < 5; ++round) {
    const double start_s = thread_cpu_s();
    for (int call = 0; call < 10; ++call) sum_effects_N(scene, at_rest, instances);
    best_s = std::min(best_s, (thread_cpu_s() - start_s) / 10);
  }
  return std::max(1000L, static_cast<long>(kTrial * 0.35e-3 / best_s));
}

bool names_scan_pace(const std::string& message, const std::string& script) {
  return message.starts_with("too slow for the 1000 Hz loop: " + script + ": force() took ") &&
         message.find(" calls of an open-loop scan") != std::string::npos;
}

}  // namespace

TEST_CASE("scan pace: a script within every limit but too slow for the checks' scans stops them, named") {
  const test::ScratchFolder folder("busy_scan");
  const std::string script = folder.write("busy.lua", busy_script(busy_iterations(folder), 1)).string();
  const Scene scene = load_environment_file(
      folder.write("busy.json", std::string(R"({"name": "busy", "effects": [{"type": "script", "file": "busy.lua", )") + kBusyLimits + "}]}")
          .string());
  // Inside every limit: a call does not fault and keeps the loop's pace.
  ScriptList one = make_script_instances(scene);
  EffectInput at_rest;
  at_rest.x_m = 0.01;
  at_rest.dt_s = scene.period_s;
  CHECK(sum_effects_N(scene, at_rest, one) == doctest::Approx(-1.0));
  CHECK_FALSE(one[0]->disabled());

  // probe (the open loop): ScriptsTooSlow, the pace check naming the script.
  std::vector<double> x_m;
  for (int i = 0; i < 4001; ++i) x_m.push_back(-0.02 + 1e-5 * i);
  OpenLoop open_loop(scene);
  try {
    open_loop.scan(x_m, 0.0);
    FAIL("the scan of 4001 points ran to its end");
  } catch (const ScriptsTooSlow& slow) {
    CHECK(slow.check().name == "pace");
    CHECK(slow.check().value > 0.1 * scene.period_s);
    CAPTURE(std::string(slow.what()));
    CHECK(names_scan_pace(slow.what(), script));
    MESSAGE(std::string(slow.what()));
  }

  // validate: the field scan fails the scene's pace check; no scenario runs.
  const ValidationReport report = validate_scene(scene, {}, {});
  CHECK_FALSE(report.pass);
  CHECK(report.scenarios.empty());
  REQUIRE(report.scene_checks.size() == 1);
  CHECK(report.scene_checks[0].name == "pace");
  CAPTURE(report.scene_checks[0].detail);
  CHECK(names_scan_pace(report.scene_checks[0].detail, script));

  // plot: the curve is not drawn.
  const PlotPanel panel = force_displacement_panel(scene);
  CHECK(panel.series.empty());
  CHECK(panel.title.find(": not drawn, too slow for the 1000 Hz loop: " + script) != std::string::npos);

  // test: the spec fails with the message alone, whatever it asks.
  const auto spec = folder.write("busy.test.json", R"({"environment": "busy.json",
      "forces": [{"x": "10 mm", "force": "-1 N", "tolerance": "1e-9 N"}],
      "zero_outside": ["-50 mm", "45 mm"], "passes_validate": true})");
  const SpecResult result = run_test_spec(spec.string());
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 1);
  CHECK(result.outcomes[0].what == "/environment");
  CAPTURE(result.outcomes[0].message);
  CHECK(names_scan_pace(result.outcomes[0].message, script));
}

TEST_CASE("scan pace: in 2-D too, test, validate and probe stop with the script named") {
  const test::ScratchFolder folder("busy_scan_2d");
  const std::string script = folder.write("busy.lua", busy_script(busy_iterations(folder), 2)).string();
  const std::string environment =
      folder.write("busy.json", std::string(R"({"name": "busy", "device": "haplink", "effects": [{"type": "script", "file": "busy.lua", )") +
                                    kBusyLimits + "}]}")
          .string();
  const PlanarScene scene = load_planar_environment_file(environment);

  PlanarOpenLoop open_loop(scene);
  CHECK_THROWS_AS(open_loop.scan(planar_workspace_grid(scene, 1e-3), Vec2{}), ScriptsTooSlow);

  const PlanarValidationReport report = validate_planar_scene(scene, {}, {});
  CHECK_FALSE(report.pass);
  CHECK(report.scenarios.empty());
  REQUIRE(report.scene_checks.size() == 1);
  CAPTURE(report.scene_checks[0].detail);
  CHECK(names_scan_pace(report.scene_checks[0].detail, script));

  const auto spec = folder.write("busy.test.json", R"({"environment": "busy.json",
      "forces": [{"at": ["-15 mm", "130 mm"], "force": ["0 N", "0 N"], "tolerance": "1e-9 N"}],
      "never_exceeds": "5 N"})");
  const SpecResult result = run_test_spec(spec.string());
  CHECK_FALSE(result.pass);
  REQUIRE(result.outcomes.size() == 1);
  CHECK(result.outcomes[0].what == "/environment");
  CAPTURE(result.outcomes[0].message);
  CHECK(names_scan_pace(result.outcomes[0].message, script));
}
