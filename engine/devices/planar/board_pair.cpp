#include "engine/devices/planar/board_pair.hpp"

#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/devices/board_report.hpp"

namespace hapscene {
namespace {

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

void require_hapkit_joints(const PlanarProfile& profile, const std::string& what) {
  for (std::size_t i = 0; i < 2; ++i) {
    const PlanarJoint& joint = profile.joints[i];
    // (An encoder joint, the Haplink's, would have its MR counts read as encoder counts:
    // the handle in the wrong place.)
    if (joint.sensor.kind == PlanarSensorKind::encoder) {
      throw InputError(what + ": profile \"" + profile.name + "\" joint " + std::to_string(i + 1) +
                       " reads an encoder, but the hapscene firmware reads the Hapkit's MR sensor (a Hapkit "
                       "pantograph's joints, \"hapkit_pantograph\", are what two boards drive; in " +
                       profile_place(profile.source, "/joints/" + std::to_string(i) + "/sensor/type") + ")");
    }
    const bool counts = joint.sensor.kind == PlanarSensorKind::mr;
    const bool duty = joint.drive.law == PlanarDriveLaw::sqrt || joint.drive.law == PlanarDriveLaw::linear;
    if (!counts || !duty) {
      throw InputError(what + ": profile \"" + profile.name + "\" joint " + std::to_string(i + 1) +
                       " is not a Hapkit board (it needs an \"mr\" sensor and a \"sqrt\" or "
                       "\"linear\" drive; a Haply-style profile runs on --device haply:PATH; in " +
                       profile_place(profile.source, "/joints/" + std::to_string(i)) + ")");
    }
  }
}

BoardLinkConfig joint_link_config(BoardLinkConfig link, const PlanarProfile& profile, std::size_t joint_index) {
  const PlanarSensor& sensor = profile.joints[joint_index].sensor;
  if (sensor.kind == PlanarSensorKind::mr && sensor.span_counts > 0) link.span_counts = sensor.span_counts;
  const double rad_per_count = std::abs(compile_planar_model(profile).joints[joint_index].rad_per_count);
  if (rad_per_count > 0.0 && std::isfinite(rad_per_count)) {
    link.max_speed_counts_per_s = kMaxJointSpeed_rad_per_s / rad_per_count;
  }
  return link;
}

bool BoardPair::both_running() const noexcept {
  return links_[0]->state() == LinkState::running && links_[1]->state() == LinkState::running;
}

void BoardPair::update_status() noexcept {
  const PositionStatus first = joint_status(*links_[0]);
  const PositionStatus second = joint_status(*links_[1]);
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

PlanarReading BoardPair::read(std::int64_t now_ns) noexcept {
  links_[0]->poll(now_ns);
  links_[1]->poll(now_ns);
  update_status();
  PlanarReading reading;
  reading.counts = {links_[0]->counts(), links_[1]->counts()};
  return reading;
}

void BoardPair::write(const PlanarMotorCommand& command, std::int64_t now_ns) noexcept {
  if (holds_force(status_) || !both_running()) {
    // Never one motor's force without the other's: both get zero.
    ++zeroed_writes_;
    links_[0]->send(MotorCommand{}, now_ns);
    links_[1]->send(MotorCommand{}, now_ns);
    return;
  }
  links_[0]->send(command.motor[0], now_ns);
  links_[1]->send(command.motor[1], now_ns);
}

void BoardPair::send_zero(std::int64_t now_ns) noexcept {
  for (BoardLink* link : links_) {
    if (link->state() == LinkState::running) link->send(MotorCommand{}, now_ns);
  }
}

bool BoardPair::take_restart() noexcept {
  // Take both links' restarts (no short circuit), and fire once both are running with a
  // fresh position.
  const bool first = links_[0]->take_restart();
  const bool second = links_[1]->take_restart();
  restart_pending_ = restart_pending_ || first || second;
  if (restart_pending_ && status_ == PositionStatus::fresh && both_running()) {
    restart_pending_ = false;
    ++restarts_;
    return true;
  }
  return false;
}

std::string BoardPair::report(const std::array<std::string, 2>& names, std::int64_t start_ns) const {
  std::string text;
  for (std::size_t i = 0; i < 2; ++i) {
    // The board's report, each line labelled with its joint.
    const std::string label = "  joint " + std::to_string(i + 1) + " ";
    text += label + printf_string("port     %s; force held %llu ticks for this board\n", names[i].c_str(),
                                  static_cast<unsigned long long>(held_ticks_[i]));
    const std::string lines = board_report(*links_[i], start_ns);
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
