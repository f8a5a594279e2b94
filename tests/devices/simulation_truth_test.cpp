// Observers (the harness recorder, `run --plot`) read a simulator's true state through
// Device::truth(): simulated devices answer it, a real device answers null and the
// record's "true" columns repeat what the host measured.
#include <doctest/doctest.h>

#include "engine/devices/open_device.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/harness/recorder.hpp"
#include "engine/run/runner.hpp"
#include "tests/support.hpp"

#if HAPSCENE_HAVE_HIL
#include "engine/devices/hil/hil_hapkit.hpp"
#endif

using namespace hapscene;

namespace {

// A device with no simulator behind it: the Device defaults, a fixed reading.
class FixedReading final : public Device {
 public:
  std::int32_t read() noexcept override { return 500; }
  void write(const MotorCommand&) noexcept override {}
};

// Runs the lab wall for `ticks` in simulated time, recording through device.truth().
std::vector<TickRecord> record_run(const Scene& scene, Device& device, std::size_t ticks) {
  Recorder recorder(device.truth(), ticks + 1);
  RunOptions options;
  options.duration_s = static_cast<double>(ticks) * scene.period_s;
  options.pacing = Pacing::simulated_time;
  run_scene(scene, device, options, &recorder);
  return recorder.take();
}

}  // namespace

TEST_CASE("simulation truth: the simulated Hapkit's records carry the plant's state, not the host's") {
  const Scene scene = test::scene_from(R"({"effects": [{"type": "wall", "position": "5 mm", "solid": "above", "stiffness": 500}]})");
  SimulationConfig config;
  config.hand.motion = HandMotion::sweep;
  SimulatedHapkit device(scene.device, config);
  REQUIRE(device.truth() == &device);
  const std::vector<TickRecord> records = record_run(scene, device, 400);
  REQUIRE(records.size() == 400);
  // The true position is continuous; the host's is quantized to the sensor's counts, so
  // they differ somewhere, and the hand's force is the plant's (nonzero while sweeping).
  bool differs = false;
  bool hand_pushes = false;
  for (const TickRecord& r : records) {
    differs = differs || r.x_true_m != r.x_m;
    hand_pushes = hand_pushes || r.hand_N != 0.0;
  }
  CHECK(differs);
  CHECK(hand_pushes);
  CHECK(records.back().x_true_m != 0.0);
}

TEST_CASE("simulation truth: a device without a simulator has none, and records repeat what the host saw") {
  const Scene scene = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  FixedReading device;
  CHECK(device.truth() == nullptr);
  for (const TickRecord& r : record_run(scene, device, 50)) {
    CHECK(r.x_true_m == r.x_m);
    CHECK(r.v_true_m_per_s == r.v_m_per_s);
    CHECK(r.motor_N == r.output_N);
    CHECK(r.hand_N == 0.0);
  }
}

#if HAPSCENE_HAVE_HIL
TEST_CASE("simulation truth: the firmware-in-the-loop device exposes its plant too") {
  const Scene scene = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 100}]})");
  HilConfig config;
  config.simulation.hand.motion = HandMotion::sweep;
  config.firmware_elf = default_firmware_elf();
  HilHapkit device(scene.device, config);
  REQUIRE(device.truth() == &device);
  const std::vector<TickRecord> records = record_run(scene, device, 300);
  REQUIRE(!records.empty());
  bool differs = false;
  for (const TickRecord& r : records) differs = differs || r.x_true_m != r.x_m;
  CHECK(differs);
}
#endif
