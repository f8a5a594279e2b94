#include "engine/devices/open_device.hpp"

#include "engine/base/errors.hpp"
#include "engine/devices/haply/haply_device.hpp"
#include "engine/devices/installed_files.hpp"
#include "engine/devices/planar/hapkit_pair.hpp"
#include "engine/devices/serial_hapkit.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#if HAPSCENE_HAVE_HIL
#include "engine/devices/hil/hil_hapkit.hpp"
#include "engine/devices/hil/hil_pair.hpp"
#endif

namespace hapscene {

std::string default_firmware_elf() { return find_default_firmware(); }

namespace {

bool is_hil(const std::string& spec) { return spec == "hil" || spec.starts_with("hil:"); }

#if HAPSCENE_HAVE_HIL
// The firmware of `hil:ELF`, or the one this build or install has (InputError when none is
// found).
std::string hil_firmware_elf(const std::string& spec) {
  const std::string elf = spec.size() > 4 ? spec.substr(4) : default_firmware_elf();
  if (elf.empty()) {
    throw InputError("--device hil: no firmware found (looked for " + firmware_places_text() +
                     "); name one with hil:PATH.elf");
  }
  return elf;
}
#else
[[noreturn]] void refuse_hil() {
  throw InputError("--device hil: this build has no firmware-in-the-loop (it needs simavr, "
                   "libsimavr-dev and the AVR toolchain when building; see .ci/install-deps)");
}
#endif

// The hapscene firmware reads an MR sensor and drives the Hapkit's sqrt law: a profile that
// describes other hardware cannot be rendered through it.
void require_hapkit_board(const std::string& spec, const DeviceProfile& profile) {
  const std::string device = spec.substr(0, spec.find(':'));
  if (profile.sensor.kind != SensorKind::mr) {
    throw InputError("--device " + device + ": profile \"" + profile.name +
                     "\" has an encoder, but the hapscene firmware reads the Hapkit's MR sensor (in " +
                     profile_place(profile.source, "/sensor/type") + ")");
  }
}

}  // namespace

bool simulates_plant(const std::string& spec) { return spec == "sim" || is_hil(spec); }

const PlanarPlant* simulated_planar_plant(const DeviceOf<2>& device) {
  if (const auto* sim = dynamic_cast<const SimulatedPlanar*>(&device)) return &sim->plant();
#if HAPSCENE_HAVE_HIL
  if (const auto* hil = dynamic_cast<const HilPair*>(&device)) return &hil->plant();
#endif
  return nullptr;
}

std::unique_ptr<Device> open_device(const std::string& spec, const DeviceProfile& profile,
                                    const SimulationConfig& simulation, const LinkOptions& link) {
  if (spec == "sim") return std::make_unique<SimulatedHapkit>(profile, simulation);
  if (spec == "serial" || spec.starts_with("serial:") || is_hil(spec)) {
    require_hapkit_board(spec, profile);
  }

  // serial:PATH
  if (spec.starts_with("serial:") || spec == "serial") {
    const std::string path = spec.size() > 7 ? spec.substr(7) : std::string();
    if (path.empty()) throw InputError("--device serial: needs a port path, e.g. serial:/dev/ttyACM0");
    if (path.find(',') != std::string::npos) {
      throw InputError("--device serial:" + path + ": two ports drive a 2-DOF scene (two Hapkit boards as one "
                       "device); this scene's device \"" + profile.name + "\" is 1-DOF and takes one port");
    }
    SerialConfig config;
    config.path = path;
    config.baud = link.baud;
    return std::make_unique<SerialHapkit>(profile, config);
  }

  // hil or hil:ELF
  if (is_hil(spec)) {
#if HAPSCENE_HAVE_HIL
    HilConfig config;
    config.simulation = simulation;
    config.firmware_elf = hil_firmware_elf(spec);
    return std::make_unique<HilHapkit>(profile, config);
#else
    refuse_hil();
#endif
  }
  if (spec == "haply" || spec.starts_with("haply:")) {
    throw InputError("--device haply: a Haply board drives a 2-DOF scene (a haply2diy_v1..v3 profile); this "
                     "scene's device \"" + profile.name + "\" is 1-DOF (available: " + kDeviceSpecs + ")");
  }
  throw InputError("--device: unknown device \"" + spec + "\" (available: " + kDeviceSpecs + ")");
}

std::unique_ptr<DeviceOf<2>> open_planar_device(const std::string& spec, const PlanarProfile& profile,
                                                const PlanarSimulationConfig& simulation, const LinkOptions& link) {
  if (spec == "sim") return std::make_unique<SimulatedPlanar>(profile, simulation);
  // serial:PATH1,PATH2: joint 1's board, then joint 2's
  if (spec == "serial" || spec.starts_with("serial:")) {
    HapkitPairConfig config;
    config.paths = parse_board_pair(spec.size() > 7 ? spec.substr(7) : std::string());
    config.baud = link.baud;
    return std::make_unique<HapkitPair>(profile, config);
  }
  if (spec == "haply" || spec.starts_with("haply:")) {
    const std::string path = spec.size() > 6 ? spec.substr(6) : std::string();
    if (path.empty()) throw InputError("--device haply: needs a port path, e.g. haply:/dev/ttyACM0");
    HaplyConfig config;
    config.path = path;
    return std::make_unique<HaplyDevice>(profile, config);
  }
  // hil or hil:ELF: two simulated boards, joint 1's and joint 2's
  if (is_hil(spec)) {
#if HAPSCENE_HAVE_HIL
    HilPairConfig config;
    config.simulation = simulation;
    config.firmware_elf = hil_firmware_elf(spec);
    return std::make_unique<HilPair>(profile, config);
#else
    refuse_hil();
#endif
  }
  throw InputError("--device: unknown device \"" + spec + "\" for a 2-DOF scene (available: " +
                   kPlanarDeviceSpecs + ")");
}

}  // namespace hapscene
