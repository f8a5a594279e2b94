#pragma once
// Opens the device named on the command line (`--device SPEC`) for a scene.
//   sim          the simulated Hapkit built from the scene's device profile
//   serial:PATH  a Hapkit running the hapscene firmware on a serial port
//   hil[:ELF]    the firmware run on a simulated ATmega328P wired to the simulated
//                Hapkit (firmware-in-the-loop; needs simavr and the AVR toolchain at
//                build time); ELF defaults to the firmware this build produced
#include <memory>
#include <string>

#include "engine/devices/device.hpp"
#include "engine/devices/hapkit_plant.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/devices/profile.hpp"

namespace hapscene {

// The device specs `open_device` understands, for messages.
inline constexpr const char* kDeviceSpecs = "sim, serial:PATH, hil";

struct LinkOptions {
  int baud{1000000};  // serial only
};

// Throws InputError for an unknown or malformed spec, or one that cannot be opened;
// std::runtime_error when a device opens but does not answer.
std::unique_ptr<Device> open_device(const std::string& spec, const DeviceProfile& profile,
                                    const SimulationConfig& simulation,
                                    const LinkOptions& link = {});

// The device specs a 2-DOF (planar) scene can run on, for messages.
inline constexpr const char* kPlanarDeviceSpecs = "sim, serial:PATH1,PATH2, hil, haply:PATH";

// Opens a 2-DOF device for a planar scene:
//   sim         the simulated linkage of the scene's profile
//   serial:PATH1,PATH2  two Hapkit boards running the hapscene firmware, joint 1's and
//               joint 2's (profiles with Hapkit-style joints: hapkit_pantograph, haplink)
//   hil[:ELF]   two simulated boards running the firmware, joint 1's and joint 2's, wired
//               to the simulated linkage in lock-step (profiles with Hapkit-style joints)
//   haply:PATH  a board running Haply's stock firmware (haply2diy_v1..v3 profiles)
// Throws as open_device does.
std::unique_ptr<DeviceOf<2>> open_planar_device(const std::string& spec, const PlanarProfile& profile,
                                                const PlanarSimulationConfig& simulation,
                                                const LinkOptions& link = {});

// Whether a device spec runs a simulated plant (sim, hil): the simulated hand, simulated
// time and the plant's true state apply.
bool simulates_plant(const std::string& spec);

// The simulated linkage under a 2-DOF device (sim or hil), or null for a real device.
const PlanarPlant* simulated_planar_plant(const DeviceOf<2>& device);

// The firmware `--device hil` loads when no ELF is named (empty when this build has none).
std::string default_firmware_elf();

}  // namespace hapscene
