#pragma once
// `hapscene run`, per device kind: what a run differs in, so that run_command.cpp is
// written once over N. Each kind's functions are overloads on its scene type:
// run_capstan.cpp for one axis (the Hapkit), run_planar.cpp for two (the planar linkages).
// A new kind adds its overloads in a file of its own.
#include <memory>
#include <string>

#include "engine/cli/arguments.hpp"
#include "engine/cli/run_settings.hpp"
#include "engine/devices/device.hpp"
#include "engine/run/tick_observer.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// The figure of `run --plot FILE.svg`: an observer that records the run in a fixed amount
// of memory (allocated before the run), and the SVG written from it afterwards.
template <int N>
class RunFigureOf {
 public:
  virtual ~RunFigureOf() = default;
  virtual TickObserverOf<N>* observer() noexcept = 0;
  // The figure, titled with the hand's name. Throws InputError when it cannot be written.
  virtual void write(const std::string& path, const std::string& hand) const = 0;
};

// Opens the device `scene` runs on: --device, with the simulated hand and the handle's
// start from --hand, --hold, --start and --noise where the device is simulated. Writes the
// hand's name for the summary. Fails `arguments` (exit 2) on an option the kind refuses.
std::unique_ptr<DeviceOf<1>> open_run_device(const Arguments& arguments, const RunSettings& settings,
                                             const SceneOf<1>& scene, std::string* hand_name);
std::unique_ptr<DeviceOf<2>> open_run_device(const Arguments& arguments, const RunSettings& settings,
                                             const SceneOf<2>& scene, std::string* hand_name);

// The figure of a run of `scene` on `device` (its truth, when simulated).
std::unique_ptr<RunFigureOf<1>> open_run_figure(const Arguments& arguments, const RunSettings& settings, const SceneOf<1>& scene,
                                                const DeviceOf<1>& device);
std::unique_ptr<RunFigureOf<2>> open_run_figure(const Arguments& arguments, const RunSettings& settings, const SceneOf<2>& scene,
                                                const DeviceOf<2>& device);

// The summary's lines of the kind's own device, before its report (the planar plant's
// linkage faults; none for a capstan device).
void print_device_lines(const DeviceOf<1>& device);
void print_device_lines(const DeviceOf<2>& device);

}  // namespace hapscene
