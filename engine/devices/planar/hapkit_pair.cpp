#include "engine/devices/planar/hapkit_pair.hpp"

#include <sys/stat.h>

#include "engine/base/clock.hpp"
#include "engine/base/errors.hpp"
#include "engine/devices/board_handshake.hpp"

namespace hapscene {
namespace {

const char* kWhat = "--device serial";

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
    throw InputError(std::string(kWhat) + ":" + paths[0] + "," + paths[1] +
                     ": both paths name the same device; joint 1 and joint 2 need one board each");
  }
}

// The paths, once the profile and the paths are known to make a two-board device.
std::array<std::string, 2> checked_paths(const PlanarProfile& profile, const HapkitPairConfig& config) {
  require_hapkit_joints(profile, kWhat);
  refuse_same_device(config.paths);
  return config.paths;
}

}  // namespace

std::array<std::string, 2> parse_board_pair(const std::string& paths_text) {
  const std::size_t comma = paths_text.find(',');
  const std::string usage = " (a 2-DOF scene takes serial:PATH1,PATH2: joint 1's board, then joint 2's)";
  if (comma == std::string::npos) {
    throw InputError(std::string(kWhat) + ":" + paths_text + ": one port for a 2-DOF scene" + usage);
  }
  const std::array<std::string, 2> paths{paths_text.substr(0, comma), paths_text.substr(comma + 1)};
  if (paths[1].find(',') != std::string::npos) {
    throw InputError(std::string(kWhat) + ":" + paths_text + ": more than two ports" + usage);
  }
  if (paths[0].empty() || paths[1].empty()) {
    throw InputError(std::string(kWhat) + ":" + paths_text + ": an empty port path" + usage);
  }
  return paths;
}

HapkitPair::HapkitPair(const PlanarProfile& profile, const HapkitPairConfig& config)
    : paths_(checked_paths(profile, config)),
      boards_{std::make_unique<Board>(paths_[0], config.baud, std::string(kWhat) + " (joint 1): " + paths_[0],
                                      joint_link_config(config.link, profile, 0)),
              std::make_unique<Board>(paths_[1], config.baud, std::string(kWhat) + " (joint 2): " + paths_[1],
                                      joint_link_config(config.link, profile, 1))},
      pair_(boards_[0]->link, boards_[1]->link) {
  start_ns_ = monotonic_now_ns();
  // Both handshakes at once: boards that reset when their port opens boot together.
  const std::array<BoardToOpen, 2> open{
      BoardToOpen{&boards_[0]->link, std::string(kWhat) + " joint 1's board " + paths_[0]},
      BoardToOpen{&boards_[1]->link, std::string(kWhat) + " joint 2's board " + paths_[1]}};
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
