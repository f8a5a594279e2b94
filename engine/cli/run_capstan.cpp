// `hapscene run` on a one-axis (capstan) device: the hand of --hand, --hold and --start
// on a line, --noise on the sensor, the device, and the run's time-series figure.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/run_kind.hpp"
#include "engine/cli/run_trace.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/harness/figures.hpp"

namespace hapscene {
namespace {

// The 1-DOF hand: --hand, --hold X, --start X, over the settings' defaults.
SimulationConfig capstan_simulation(const Arguments& arguments, const RunSettings& settings) {
  SimulationConfig simulation = settings.simulation;
  HandConfig& hand = simulation.hand;
  if (const auto& motion = settings.hand_text) {
    const auto* found = std::find(std::begin(kHandMotionNames), std::end(kHandMotionNames), *motion);
    if (found == std::end(kHandMotionNames) || *found == "path") {
      arguments.fail("--hand: unknown motion \"" + *motion + "\" (use sweep, hold, release, shake or none)");
    }
    hand.motion = static_cast<HandMotion>(found - std::begin(kHandMotionNames));
  }
  if (settings.hold_text) hand.hold_m = parse_option_quantity(*settings.hold_text, option::hold, "hapscene run: --hold");
  if (settings.start_text) {
    simulation.start_x_m = parse_option_quantity(*settings.start_text, option::run_start, "hapscene run: --start");
  }
  return simulation;
}

// The time series of the run, decimated for long runs (run_trace.hpp).
class CapstanRunFigure final : public RunFigureOf<1> {
 public:
  CapstanRunFigure(const Scene& scene, const Device& device, std::uint64_t planned_ticks)
      : scene_(scene), trace_(device.truth(), planned_ticks) {}

  TickObserver* observer() noexcept override { return &trace_; }

  void write(const std::string& path, const std::string& hand) const override {
    std::string what = "run, hand " + hand;
    if (trace_.ticks_per_bucket() > 1) {
      what += ", lowest and highest force of every " + std::to_string(trace_.ticks_per_bucket()) + " ticks";
    }
    write_output_file(path, run_figure_svg(scene_, trace_.records(), what));
  }

 private:
  const Scene& scene_;
  RunTrace trace_;
};

}  // namespace

std::unique_ptr<Device> open_run_device(const Arguments& arguments, const RunSettings& settings, const Scene& scene,
                                        std::string* hand_name) {
  const SimulationConfig simulation = capstan_simulation(arguments, settings);
  *hand_name = kHandMotionNames[static_cast<int>(simulation.hand.motion)];
  DeviceProfile profile = scene.device;
  if (settings.noise_counts >= 0.0) profile.plant.sensor_noise_counts = settings.noise_counts;
  try {
    return open_device(settings.device, profile, simulation, settings.link);
  } catch (const InputError& error) {
    arguments.fail(error.what());
  }
}

std::unique_ptr<RunFigureOf<1>> open_run_figure(const Arguments& /*arguments*/, const RunSettings& settings, const Scene& scene, const Device& device) {
  const auto ticks = static_cast<std::uint64_t>(std::llround(settings.options.duration_s * scene.rate_hz));
  return std::make_unique<CapstanRunFigure>(scene, device, ticks);
}

void print_device_lines(const Device& /*device*/) {}

}  // namespace hapscene
