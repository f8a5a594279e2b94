#include "engine/devices/open_device.hpp"

#include "engine/core/errors.hpp"

namespace hapscene {

std::unique_ptr<Device> open_device(const std::string& spec, const DeviceProfile& profile,
                                    const SimulationConfig& simulation) {
  if (spec == "sim") return std::make_unique<SimulatedHapkit>(profile, simulation);
  throw InputError("--device: unknown device \"" + spec + "\" (available: " + kDeviceSpecs + ")");
}

}  // namespace hapscene
