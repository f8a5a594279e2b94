// Storms: garbage from the sensor, from the physics and from scripts. Whatever comes in,
// the command stays finite and within the limits, and every fault is counted.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/runner.hpp"
#include "engine/scene/step.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// A device whose sensor returns garbage: any int32, extremes included (seeded, portable).
class GarbageDevice final : public Device {
 public:
  std::int32_t read() noexcept override {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    const auto bits = static_cast<std::uint32_t>(state_ >> 32);
    switch (bits % 8) {
      case 0: return std::numeric_limits<std::int32_t>::max();
      case 1: return std::numeric_limits<std::int32_t>::min();
      case 2: return static_cast<std::int32_t>(bits % 1024);  // looks like a reading
      default: return static_cast<std::int32_t>(bits);
    }
  }
  void write(const MotorCommand& command) noexcept override { last = command; }
  MotorCommand last;

 private:
  std::uint64_t state_{12345};
};

// Checks every tick's command, and counts independently what the safety stage must count.
class CommandChecker final : public TickObserver {
 public:
  CommandChecker(const Scene& scene) : scene_(scene) {}
  void on_tick(const TickState& s) noexcept override {
    ++ticks;
    if (!std::isfinite(s.output_N) || std::abs(s.output_N) > scene_.safety.max_force_N) ++bad_outputs;
    if (!(s.command.duty >= 0.0 && s.command.duty <= scene_.device_model.kinematics.duty_max)) ++bad_outputs;
    if (!std::isfinite(s.x_m)) ++nonfinite_positions;
    if (!std::isfinite(s.effects_force_N)) ++nonfinite_requests;
    else if (!(s.x_m >= scene_.safety.workspace_min_m && s.x_m <= scene_.safety.workspace_max_m)) ++outside;
    else if (std::abs(s.effects_force_N) > scene_.safety.max_force_N) ++over_limit;
  }
  const Scene& scene_;
  std::uint64_t ticks{}, bad_outputs{}, nonfinite_positions{}, nonfinite_requests{}, outside{}, over_limit{};
};

RunOptions sim(double duration_s) { return RunOptions{.duration_s = duration_s, .pacing = Pacing::simulated_time}; }

}  // namespace

TEST_CASE("storm: garbage sensor readings (any int32) never give a bad command, and are counted") {
  const Scene scene = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 300},
    {"type": "damper", "damping": 2}, {"type": "texture", "width": 0.002, "damping": 5}]})");
  GarbageDevice device;
  CommandChecker checker(scene);
  const RunSummary summary = run_scene(scene, device, sim(100.0), &checker);  // 100 000 ticks
  CHECK(checker.ticks == 100000);
  CHECK(checker.bad_outputs == 0);
  CHECK(checker.nonfinite_positions == 0);
  CHECK(checker.outside > 50000);  // most garbage lands outside the workspace
  CHECK(summary.safety.outside_workspace_ticks == checker.outside);
  CHECK(summary.safety.clamped_ticks == checker.over_limit);
  CHECK(summary.safety.nonfinite_faults == checker.nonfinite_requests);
  CHECK(device.last.duty == 0.0);  // the run ends on zero force
}

TEST_CASE("storm: forces that overflow to infinity or NaN are faults, counted tick by tick") {
  // 200 springs at the largest stiffness a double holds: their sum overflows to +-inf away
  // from the centre; a huge damper turns inf - inf into NaN once the handle moves. (A file
  // can no longer give such gains: they are set after loading, to test the safety stage.)
  std::string effects = R"({"type": "damper", "damping": 1})";
  for (int i = 0; i < 200; ++i) effects += R"(, {"type": "spring", "stiffness": 1, "center": 0.001})";
  Scene scene = test::scene_from(R"({"effects": [)" + effects + "]}");
  for (Spring& spring : scene.bank.group<Spring>()) spring.stiffness_N_per_m = 1e308;
  for (Damper& damper : scene.bank.group<Damper>()) damper.damping_N_s_per_m = 1e308;
  SimulationConfig config;
  config.hand.motion = HandMotion::sweep;
  SimulatedHapkit device(scene.device, config);
  CommandChecker checker(scene);
  const RunSummary summary = run_scene(scene, device, sim(5.0), &checker);
  CHECK(checker.bad_outputs == 0);
  CHECK(checker.nonfinite_requests > 100);
  CHECK(summary.safety.nonfinite_faults == checker.nonfinite_requests);
  CHECK(summary.safety.clamped_ticks == checker.over_limit);
  CHECK(std::isfinite(device.x_m()));
}

TEST_CASE("storm: a blown-up simulation (huge plant parameters) is a counted sensor fault, not undefined behaviour") {
  // A 1 ug handle on a 20 kN/mm end stop, integrated explicitly at 1 ms: Euler diverges.
  DeviceProfile profile = test::scene_from(R"({"effects": []})").device;
  profile.plant.mass_kg = 1e-9;
  profile.plant.end_stop_stiffness_N_per_m = 2e7;
  SimulationConfig config;
  config.integrator = PlantIntegrator::semi_implicit_euler;
  config.substeps_per_tick = 1;
  config.start_x_m = 0.004;
  config.hand.motion = HandMotion::hold;
  config.hand.hold_m = 0.06;  // pulls it into the upper stop
  HapkitPlant plant(profile, config);
  std::int32_t counts = 0;
  for (int i = 0; i < 2000; ++i) {
    counts = plant.sensor_counts();
    plant.substep(1e-3, 0.0);
  }
  CHECK_FALSE(std::isfinite(plant.x_m()));
  CHECK(plant.sensor_faults() > 0);
  CHECK(counts >= profile.sensor.min_counts);
  CHECK(counts < profile.sensor.min_counts + profile.sensor.span_counts);

  // The same plant with the exact integrator stays finite: it is stable for any stiffness.
  config.integrator = PlantIntegrator::exact;
  HapkitPlant exact(profile, config);
  for (int i = 0; i < 2000; ++i) exact.substep(1e-3, 0.0);
  CHECK(std::isfinite(exact.x_m()));
  CHECK(exact.x_m() > profile.plant.end_stop_max_m);
}

TEST_CASE("storm: a script returning garbage at random ticks is clamped, then disabled, and all of it counted") {
  // Seeded random garbage: huge finite forces at random ticks (clamped), and after a
  // random while NaN (a fault that disables the script: 0 N from then on).
  const Scene scene = test::scene_from(R"({"effects": [{"type": "script", "source":
    "math.randomseed(42)\nlocal n = 0\nlocal nan_at = math.random(2000, 4000)\nfunction force(s)\n  n = n + 1\n  if n == nan_at then return 0/0 end\n  local r = math.random()\n  if r < 0.05 then return 1e300 elseif r < 0.1 then return -1e300 elseif r < 0.12 then return 5e307 end\n  return 0.5 * (math.random() - 0.5)\nend"}]})");
  SimulationConfig config;
  config.hand.motion = HandMotion::shake;
  SimulatedHapkit device(scene.device, config);
  CommandChecker checker(scene);
  const RunSummary summary = run_scene(scene, device, sim(10.0), &checker);
  CHECK(checker.bad_outputs == 0);
  CHECK(checker.over_limit > 100);
  CHECK(summary.safety.clamped_ticks == checker.over_limit);
  REQUIRE(summary.scripts.size() == 1);
  CHECK(summary.scripts[0].disabled);
  CHECK(summary.scripts[0].fault.find("expected a finite number") != std::string::npos);
  CHECK(summary.script_errors == 1);
  const double fault_s = summary.scripts[0].fault_time_s;
  CHECK(fault_s >= 2.0);
  CHECK(fault_s < 4.0);
  CHECK(summary.scripts[0].skipped_calls == summary.ticks - std::llround(fault_s * 1000.0) - 1);
  CHECK(std::isfinite(device.x_m()));
}
