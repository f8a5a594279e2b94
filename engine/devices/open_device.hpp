#pragma once
// Opens the device named on the command line (`--device SPEC`) for a scene.
//   sim   the simulated Hapkit built from the scene's device profile
#include <memory>
#include <string>

#include "engine/devices/device.hpp"
#include "engine/devices/profile.hpp"
#include "engine/devices/simulated_hapkit.hpp"

namespace hapscene {

// The device specs `open_device` understands, for messages.
inline constexpr const char* kDeviceSpecs = "sim";

// Throws InputError for an unknown spec or one that cannot be opened.
std::unique_ptr<Device> open_device(const std::string& spec, const DeviceProfile& profile,
                                    const SimulationConfig& simulation);

}  // namespace hapscene
