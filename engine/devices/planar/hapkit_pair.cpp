#include "engine/devices/planar/hapkit_pair.hpp"

#include <sys/stat.h>

#include <cmath>

#include "engine/base/clock.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/devices/board_handshake.hpp"
#include "engine/devices/board_report.hpp"
#include "engine/devices/planar/planar_model.hpp"

namespace hapscene {
namespace {

const char* kWhat = "--device serial";

// The hapscene firmware drives one joint: it reads the Hapkit's MR sensor and takes a duty.
// (An encoder joint, the Haplink's, would have its MR counts read as encoder counts: the
// handle in the wrong place.)
void require_hapkit_joints(const PlanarProfile& profile) {
  for (std::size_t i = 0; i < 2; ++i) {
    const PlanarJoint& joint = profile.joints[i];
    if (joint.sensor.kind == PlanarSensorKind::encoder) {
      throw InputError(std::string(kWhat) + ": profile \"" + profile.name + "\" joint " + std::to_string(i + 1) +
                       " reads an encoder, but the hapscene firmware reads the Hapkit's MR sensor (a Hapkit "
                       "pantograph's joints, \"hapkit_pantograph\", are what two boards drive)");
    }
    const bool counts = joint.sensor.kind == PlanarSensorKind::mr;
    const bool duty = joint.drive.law == PlanarDriveLaw::sqrt || joint.drive.law == PlanarDriveLaw::linear;
    if (!counts || !duty) {
      throw InputError(std::string(kWhat) + ": profile \"" + profile.name + "\" joint " + std::to_string(i + 1) +
                       " is not a Hapkit board (it needs an \"mr\" sensor and a \"sqrt\" or "
                       "\"linear\" drive; a Haply-style profile runs on --device haply:PATH)");
    }
  }
}

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

// Joint i's link: the sensor period (MR) for realigning after a reset, and the speed bound
// in that joint's counts.
BoardLinkConfig joint_link_config(BoardLinkConfig link, const PlanarProfile& profile, std::size_t i) {
  const PlanarSensor& sensor = profile.joints[i].sensor;
  if (sensor.kind == PlanarSensorKind::mr && sensor.span_counts > 0) link.span_counts = sensor.span_counts;
  const double rad_per_count = std::abs(compile_planar_model(profile).joints[i].rad_per_count);
  if (rad_per_count > 0.0 && std::isfinite(rad_per_count)) {
    link.max_speed_counts_per_s = kMaxJointSpeed_rad_per_s / rad_per_count;
  }
  return link;
}

int rank(PositionStatus status) noexcept {
  switch (status) {
    case PositionStatus::fresh: return 0;
    case PositionStatus::stale: return 1;
    case PositionStatus::unmeasured: return 2;
    case PositionStatus::implausible: return 3;
  }
  return 3;
}

bool holds_force(PositionStatus status) noexcept {
  return status == PositionStatus::unmeasured || status == PositionStatus::implausible;
}

// A joint's own status: a link that is not running has no position to trust.
PositionStatus joint_status(const BoardLink& link) noexcept {
  if (link.state() != LinkState::running && rank(link.position_status()) < rank(PositionStatus::unmeasured)) {
    return PositionStatus::unmeasured;
  }
  return link.position_status();
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

HapkitPair::HapkitPair(const PlanarProfile& profile, const HapkitPairConfig& config) : paths_(config.paths) {
  require_hapkit_joints(profile);
  refuse_same_device(paths_);
  for (std::size_t i = 0; i < 2; ++i) {
    boards_[i] = std::make_unique<Board>(paths_[i], config.baud,
                                         std::string(kWhat) + " (joint " + std::to_string(i + 1) + "): " + paths_[i],
                                         joint_link_config(config.link, profile, i));
  }
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

HapkitPair::~HapkitPair() {
  const std::int64_t now_ns = monotonic_now_ns();
  for (const auto& board : boards_) {
    if (board->link.state() == LinkState::running) board->link.send(MotorCommand{}, now_ns);
  }
}

void HapkitPair::update_status() noexcept {
  const PositionStatus first = joint_status(boards_[0]->link);
  const PositionStatus second = joint_status(boards_[1]->link);
  PositionStatus worse = rank(first) >= rank(second) ? first : second;
  // One stale joint beside a fresh one: the pose mixes two moments, so no force at all.
  if (worse == PositionStatus::stale && (first == PositionStatus::fresh || second == PositionStatus::fresh)) {
    worse = PositionStatus::unmeasured;
  }
  // Force held after it was rendered: the next fresh tick starts both motors again.
  if (holds_force(worse) && seen_fresh_) restart_pending_ = true;
  if (worse == PositionStatus::fresh) seen_fresh_ = true;
  status_ = worse;
  if (first != PositionStatus::fresh) ++held_ticks_[0];
  if (second != PositionStatus::fresh) ++held_ticks_[1];
}

PlanarReading HapkitPair::read() noexcept {
  const std::int64_t now_ns = monotonic_now_ns();
  boards_[0]->link.poll(now_ns);
  boards_[1]->link.poll(now_ns);
  update_status();
  PlanarReading reading;
  reading.counts = {boards_[0]->link.counts(), boards_[1]->link.counts()};
  return reading;
}

void HapkitPair::write(const PlanarMotorCommand& command) noexcept {
  const std::int64_t now_ns = monotonic_now_ns();
  const bool both_running =
      boards_[0]->link.state() == LinkState::running && boards_[1]->link.state() == LinkState::running;
  if (holds_force(status_) || !both_running) {
    // Never one motor's force without the other's: both get zero.
    ++zeroed_writes_;
    boards_[0]->link.send(MotorCommand{}, now_ns);
    boards_[1]->link.send(MotorCommand{}, now_ns);
    return;
  }
  boards_[0]->link.send(command.motor[0], now_ns);
  boards_[1]->link.send(command.motor[1], now_ns);
}

bool HapkitPair::take_restart() noexcept {
  // Take both links' restarts (no short circuit), and fire once both are running with a
  // fresh position.
  const bool first = boards_[0]->link.take_restart();
  const bool second = boards_[1]->link.take_restart();
  restart_pending_ = restart_pending_ || first || second;
  if (restart_pending_ && status_ == PositionStatus::fresh && boards_[0]->link.state() == LinkState::running &&
      boards_[1]->link.state() == LinkState::running) {
    restart_pending_ = false;
    ++restarts_;
    return true;
  }
  return false;
}

bool HapkitPair::fault_seen() const noexcept {
  return boards_[0]->link.fault_seen() || boards_[1]->link.fault_seen();
}

std::string HapkitPair::report() const {
  std::string text;
  for (std::size_t i = 0; i < 2; ++i) {
    // The board's report, each line labelled with its joint.
    const std::string label = "  joint " + std::to_string(i + 1) + " ";
    text += label + printf_string("port     %s; force held %llu ticks for this board\n", paths_[i].c_str(),
                                  static_cast<unsigned long long>(held_ticks_[i]));
    const std::string lines = board_report(boards_[i]->link, start_ns_);
    for (std::size_t begin = 0; begin < lines.size();) {
      std::size_t end = lines.find('\n', begin);
      if (end == std::string::npos) end = lines.size() - 1;
      const std::size_t body = lines.compare(begin, 2, "  ") == 0 ? begin + 2 : begin;
      text += label + lines.substr(body, end + 1 - body);
      begin = end + 1;
    }
  }
  text += printf_string("  two boards       %llu ticks zero on both motors, %llu restarts of both together\n",
                        static_cast<unsigned long long>(zeroed_writes_), static_cast<unsigned long long>(restarts_));
  return text;
}

}  // namespace hapscene
