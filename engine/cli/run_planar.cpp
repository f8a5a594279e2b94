// `hapscene run` on a two-axis (planar) device: the hand of --hand, --hold X,Y and
// --start X,Y over the scene's workspace, the device (simulated, on boards, or a Haply
// 2DIY), the run's figure in the plane, and the plant's linkage faults.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/planar_run_hand.hpp"
#include "engine/cli/run_kind.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/devices/planar/planar_hand.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/harness/planar_figure.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/planar_trace.hpp"

namespace hapscene {
namespace {

// Where the handle starts: --start, else the profile's home.
Vec2 planar_start_m(const Arguments& arguments, const RunSettings& settings, const PlanarScene& scene) {
  return settings.start_text ? parse_planar_point(arguments, "start", *settings.start_text, option::run_start)
                             : scene.device.home_m;
}

// The hand of a planar run: --hand over the scene's workspace box (planar_run_hand.hpp),
// holding or releasing at --hold (default the start).
PlanarHandConfig planar_hand(const Arguments& arguments, const RunSettings& settings, const PlanarScene& scene,
                             const Vec2& start_m) {
  PlanarHandConfig hand;
  hand.motion = PlanarHandMotion::sweep;
  if (const auto& motion = settings.hand_text) {
    const auto* found = std::find(std::begin(kPlanarHandMotionNames), std::end(kPlanarHandMotionNames), *motion);
    if (found == std::end(kPlanarHandMotionNames) || *found == "path") {
      arguments.fail("--hand: unknown motion \"" + *motion +
                     "\" (a 2-DOF run takes sweep, line, circle, hold, release, shake or none)");
    }
    hand.motion = static_cast<PlanarHandMotion>(found - std::begin(kPlanarHandMotionNames));
  }
  const Vec2 hold_m =
      settings.hold_text ? parse_planar_point(arguments, "hold", *settings.hold_text, option::hold) : start_m;
  // A hold the linkage cannot reach would pin the handle against its stops.
  if (settings.hold_text) {
    try {
      (void)planar_joint_angles_at(scene.device, hold_m);
    } catch (const InputError& error) {
      arguments.fail(std::string("--hold: ") + error.what());
    }
  }
  return planar_run_hand(scene, hand.motion, settings.simulation.hand, hold_m);
}

// The run in the plane: the handle's path and the proxy of the shape nearest the start
// (planar_trace.hpp, planar_figure.hpp).
class PlanarRunFigure final : public RunFigureOf<2> {
 public:
  PlanarRunFigure(const PlanarScene& scene, const DeviceOf<2>& device, std::uint64_t planned_ticks, int proxy_index)
      : scene_(scene), proxy_index_(proxy_index), trace_(device.truth(), planned_ticks, proxy_index) {}

  TickObserverOf<2>* observer() noexcept override { return &trace_; }

  void write(const std::string& path, const std::string& hand) const override {
    std::string what = "run, hand " + hand;
    if (trace_.ticks_per_bucket() > 1) {
      what += ", first tick and highest force of every " + std::to_string(trace_.ticks_per_bucket()) + " ticks";
    }
    const std::string proxy_label =
        proxy_index_ >= 0 ? std::string("proxy of the ") +
                                planar_shape_kind_name(planar_shape_list(scene_)[static_cast<std::size_t>(proxy_index_)].kind)
                          : std::string();
    write_output_file(path, planar_figure_svg(scene_, PlanarFigureOptions{}, trace_.records(), what, proxy_label));
  }

 private:
  const PlanarScene& scene_;
  int proxy_index_;
  PlanarTrace trace_;
};

}  // namespace

std::unique_ptr<DeviceOf<2>> open_run_device(const Arguments& arguments, const RunSettings& settings,
                                             const PlanarScene& scene, std::string* hand_name) {
  if (settings.noise_counts >= 0.0) arguments.fail("--noise: not yet for a 2-DOF environment");
  // The simulated linkage, alone or under two simulated boards: the hand and simulated time apply.
  const bool simulated = simulates_plant(settings.device);
  if (!simulated && (settings.hand_text || settings.hold_text || settings.start_text)) {
    arguments.fail(std::string(settings.hand_text ? "--hand" : settings.hold_text ? "--hold" : "--start") +
                   ": the simulated device's option; --device " + settings.device + " is a real one");
  }
  if (!simulated && settings.options.pacing == Pacing::simulated_time) {
    arguments.fail("--sim-time: --device " + settings.device + " is a real device, which runs in real time");
  }
  const Vec2 start_m = planar_start_m(arguments, settings, scene);
  PlanarSimulationConfig simulation;
  if (simulated) simulation.hand = planar_hand(arguments, settings, scene, start_m);
  simulation.noise_seed = settings.simulation.noise_seed;
  if (simulated) {
    try {
      simulation.start_q_rad = planar_joint_angles_at(scene.device, start_m);
    } catch (const InputError& error) {
      arguments.fail(std::string("--start: ") + error.what());
    }
  }
  *hand_name = simulated ? std::string(kPlanarHandMotionNames[static_cast<int>(simulation.hand.motion)])
                         : std::string("yours");
  try {
    return open_planar_device(settings.device, scene.device, simulation, settings.link);
  } catch (const InputError& error) {
    arguments.fail(error.what());
  }
}

std::unique_ptr<RunFigureOf<2>> open_run_figure(const Arguments& arguments, const RunSettings& settings, const PlanarScene& scene,
                                                const DeviceOf<2>& device) {
  const Vec2 start_m = planar_start_m(arguments, settings, scene);
  const int proxy_index = nearest_shape_index(planar_shape_list(scene), start_m);
  const auto ticks = static_cast<std::uint64_t>(std::llround(settings.options.duration_s * scene.rate_hz));
  return std::make_unique<PlanarRunFigure>(scene, device, ticks, proxy_index);
}

void print_device_lines(const DeviceOf<2>& device) {
  if (const PlanarPlant* plant = simulated_planar_plant(device)) {
    print_out("  plant            %llu linkage faults (the linkage at the edge of closing)\n",
              static_cast<unsigned long long>(plant->linkage_faults()));
  }
}

}  // namespace hapscene
