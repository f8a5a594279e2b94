#include "engine/devices/planar/hapkit_pair.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "engine/base/clock.hpp"
#include "engine/base/errors.hpp"
#include "engine/devices/board_handshake.hpp"
#include "engine/devices/port_list.hpp"

namespace hapscene {
namespace {

const char* kSerialPairWhat = "--device serial";

// Two paths naming one device (the same string, a symlink to the other, or the same
// character device) would drive one board as both joints.
void refuse_same_device(const std::array<std::string, 2>& paths) {
  bool same = paths[0] == paths[1];
  struct stat a{}, b{};
  if (!same && stat(paths[0].c_str(), &a) == 0 && stat(paths[1].c_str(), &b) == 0) {
    same = (a.st_dev == b.st_dev && a.st_ino == b.st_ino) ||
           (S_ISCHR(a.st_mode) && S_ISCHR(b.st_mode) && a.st_rdev == b.st_rdev);
  }
  if (same) {
    throw InputError(std::string(kSerialPairWhat) + ":" + paths[0] + "," + paths[1] +
                     ": both paths name the same device; joint 1 and joint 2 need one board each");
  }
}

// The USB serial number of the board on `path` (a /dev/ttyACM* node or a by-id link, under
// `root`) among `ports` (listed under `root`), or "" when it has none or is not listed.
std::string usb_serial_of(const std::string& path, const std::string& root, const std::vector<SerialPortEntry>& ports) {
  namespace fs = std::filesystem;
  const bool under_root = root.empty() || root == "/" || path.starts_with(root);
  const std::string listed = under_root ? fs::path(path).lexically_normal().string()
                                        : (fs::path(root) / fs::path(path).relative_path()).lexically_normal().string();
  for (const SerialPortEntry& port : ports) {
    const bool named = port.path == listed || std::find(port.by_id.begin(), port.by_id.end(), listed) != port.by_id.end();
    if (named) return port.serial;
  }
  // Another link to one of them (/dev/serial/by-path/...): the same device node.
  std::error_code error;
  const fs::path target = fs::canonical(listed, error);
  if (error) return {};
  for (const SerialPortEntry& port : ports) {
    std::error_code port_error;
    if (fs::canonical(port.path, port_error) == target && !port_error) return port.serial;
  }
  return {};
}

// The paths, once the profile and the paths are known to make a two-board device.
std::array<std::string, 2> checked_paths(const PlanarProfile& profile, const HapkitPairConfig& config) {
  require_hapkit_joints(profile, kSerialPairWhat);
  refuse_same_device(config.paths);
  check_board_identities(profile, config.paths, devices_root());
  return config.paths;
}

}  // namespace

void check_board_identities(const PlanarProfile& profile, const std::array<std::string, 2>& paths,
                            const std::string& devices_root) {
  const std::array<std::string, 2>& wanted = profile.board_serials;
  if (wanted[0].empty() && wanted[1].empty()) return;
  const std::string place = " (in " + profile_place(profile.source, "/board_serials") + ")";
  const std::vector<SerialPortEntry> ports = list_serial_ports(devices_root);
  const std::array<std::string, 2> found{usb_serial_of(paths[0], devices_root, ports),
                                         usb_serial_of(paths[1], devices_root, ports)};
  if (found[0] == wanted[1] && found[1] == wanted[0]) {
    throw InputError(std::string(kSerialPairWhat) + ":" + paths[0] + "," + paths[1] + ": the cables are swapped: " + paths[0] +
                     " is joint 2's board (USB serial " + found[0] + ") and " + paths[1] + " joint 1's (" + found[1] +
                     "), as profile \"" + profile.name + "\" names them; give serial:" + paths[1] + "," + paths[0] + place);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    if (found[i] == wanted[i]) continue;
    const std::string joint = "joint " + std::to_string(i + 1);
    if (found[i].empty()) {
      throw InputError(std::string(kSerialPairWhat) + " (" + joint + "): " + paths[i] +
                       ": no USB serial number to check against profile \"" + profile.name + "\"'s board_serials (\"" +
                       wanted[i] + "\"): not a USB board, or one without a serial number (`hapscene devices` lists them)" + place);
    }
    throw InputError(std::string(kSerialPairWhat) + " (" + joint + "): " + paths[i] + " is the board with USB serial " + found[i] +
                     ", not " + joint + "'s (\"" + wanted[i] + "\") as profile \"" + profile.name + "\" names it" + place);
  }
}

std::array<std::string, 2> parse_board_pair(const std::string& paths_text) {
  const std::size_t comma = paths_text.find(',');
  const std::string usage = " (a 2-DOF scene takes serial:PATH1,PATH2: joint 1's board, then joint 2's)";
  if (comma == std::string::npos) {
    throw InputError(std::string(kSerialPairWhat) + ":" + paths_text + ": one port for a 2-DOF scene" + usage);
  }
  const std::array<std::string, 2> paths{paths_text.substr(0, comma), paths_text.substr(comma + 1)};
  if (paths[1].find(',') != std::string::npos) {
    throw InputError(std::string(kSerialPairWhat) + ":" + paths_text + ": more than two ports" + usage);
  }
  if (paths[0].empty() || paths[1].empty()) {
    throw InputError(std::string(kSerialPairWhat) + ":" + paths_text + ": an empty port path" + usage);
  }
  return paths;
}

HapkitPair::HapkitPair(const PlanarProfile& profile, const HapkitPairConfig& config)
    : paths_(checked_paths(profile, config)),
      boards_{std::make_unique<Board>(paths_[0], config.baud, std::string(kSerialPairWhat) + " (joint 1): " + paths_[0],
                                      joint_link_config(config.link, profile, 0)),
              std::make_unique<Board>(paths_[1], config.baud, std::string(kSerialPairWhat) + " (joint 2): " + paths_[1],
                                      joint_link_config(config.link, profile, 1))},
      pair_(boards_[0]->link, boards_[1]->link) {
  start_ns_ = monotonic_now_ns();
  // Both handshakes at once: boards that reset when their port opens boot together.
  const std::array<BoardToOpen, 2> open{
      BoardToOpen{&boards_[0]->link, std::string(kSerialPairWhat) + " joint 1's board " + paths_[0]},
      BoardToOpen{&boards_[1]->link, std::string(kSerialPairWhat) + " joint 2's board " + paths_[1]}};
  complete_handshakes(open, config.handshake_timeout_s, config.baud);
  // The run's own soft start covers the first contact.
  (void)boards_[0]->link.take_restart();
  (void)boards_[1]->link.take_restart();
}

HapkitPair::~HapkitPair() { pair_.send_zero(monotonic_now_ns()); }

PlanarReading HapkitPair::read() noexcept { return pair_.read(monotonic_now_ns()); }

void HapkitPair::write(const PlanarMotorCommand& command) noexcept { pair_.write(command, monotonic_now_ns()); }

std::string HapkitPair::report() const { return pair_.report(paths_, start_ns_); }

}  // namespace hapscene
