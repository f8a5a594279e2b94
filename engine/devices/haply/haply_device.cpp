#include "engine/devices/haply/haply_device.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

#include "engine/base/clock.hpp"
#include "engine/base/format.hpp"

namespace hapscene {

HaplyDevice::HaplyDevice(const PlanarProfile& profile, const HaplyConfig& config)
    : setup_(haply_setup_for(profile, config.id)),
      port_(config.path, 115200, "--device haply:" + config.path),
      link_(port_, setup_, config.link, monotonic_now_ns()),
      start_ns_(monotonic_now_ns()) {
  // The first reply, before the loop starts (the board answers within a millisecond).
  const auto deadline_ns = start_ns_ + static_cast<std::int64_t>(config.handshake_timeout_s * 1e9);
  while (link_.state() != HaplyLinkState::running) {
    const std::int64_t now_ns = monotonic_now_ns();
    if (now_ns > deadline_ns) {
      const HaplyLinkCounters& c = link_.counters();
      const std::string rejected =
          c.implausible == 0 ? std::string()
                             : std::to_string(c.implausible) + " rejected as implausible (the first: an angle " +
                                   reading_fault_name(c.first_implausible_fault) + "), ";
      throw std::runtime_error("--device haply:" + config.path + (c.implausible == 0 ? ": no reply" : ": no plausible reply") +
                               " to the setup within " + printf_string("%g", config.handshake_timeout_s) + " s (" +
                               std::to_string(c.replies) + " replies, " + rejected + std::to_string(c.bytes_dropped) +
                               " bytes that made no reply; is it a Haply board with its stock firmware, its arm at "
                               "the reference pose?)");
    }
    link_.poll(now_ns);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  handshake_resyncs_ = link_.counters().resyncs;
  handshake_implausible_ = link_.counters().implausible;
  (void)link_.take_restart();  // the run's own soft start covers the first contact
  if (config.watchdog) {
    watchdog_ = std::make_unique<ZeroTorqueWatchdog>(config.path, encode_torques(setup_, Vec2{}),
                                                     config.watchdog_stall_ns);
  }
}

HaplyDevice::~HaplyDevice() {
  // Twice: a board whose parser was mid-frame takes the first as the frame's end. Then
  // wait (up to 200 ms) until the port has taken every byte: the board keeps the last
  // torque it got.
  link_.send_zero();
  link_.send_zero();
  (void)link_.drain_tx(200);
  // Destroying the watchdog tells it this was a clean end.
}

PlanarReading HaplyDevice::read() noexcept {
  link_.poll(monotonic_now_ns());
  PlanarReading reading;
  reading.angle_deg = link_.angles_deg();
  return reading;
}

void HaplyDevice::write(const PlanarMotorCommand& command) noexcept {
  // The watchdog hears of a torque before the board does: a process stopped between the
  // two must not leave a torque on that the watchdog thinks is off.
  if (watchdog_) {
    const bool torque_on = link_.state() == HaplyLinkState::running &&
                           (command.torque_N_m[0] != 0.0 || command.torque_N_m[1] != 0.0);
    watchdog_->beat(torque_on);
  }
  link_.send(command.torque_N_m, monotonic_now_ns());
}

bool HaplyDevice::take_restart() noexcept {
  bool restart = link_.take_restart();
  // The watchdog zeroed the torque while this process stalled: ramp in again.
  if (watchdog_ && watchdog_->take_fired()) {
    ++watchdog_restarts_;
    restart = true;
  }
  return restart;
}

bool HaplyDevice::fault_seen() const noexcept {
  return link_.counters().resyncs > handshake_resyncs_ || link_.counters().implausible > handshake_implausible_ ||
         (watchdog_ && watchdog_->fired() > 0);
}

void HaplyDevice::link_health(DeviceLinkHealth* out) const noexcept {
  const HaplyLinkCounters& c = link_.counters();
  LinkHealth h;
  h.protocol = "haply";
  h.state = link_.state() == HaplyLinkState::running ? "running"
            : link_.state() == HaplyLinkState::vanished ? "vanished" : "handshaking";
  h.commands = c.frames_sent;
  h.replies = c.replies;
  h.frames_not_sent = c.frames_dropped;
  h.bytes_skipped = c.bytes_dropped;
  h.resyncs = c.resyncs;
  h.implausible = c.implausible;
  h.silences = c.by_reason[static_cast<std::size_t>(HaplyResyncReason::silence)];
  h.vanished = c.by_reason[static_cast<std::size_t>(HaplyResyncReason::vanished)];
  out->links = 1;
  out->link[0] = h;
}

std::string HaplyDevice::report() const {
  std::string text = link_.report(start_ns_);
  if (handshake_resyncs_ > 0 || handshake_implausible_ > 0) {
    text += printf_string("  opening          %llu of the resyncs and %llu of the implausible replies were before the "
                          "first reply\n",
                          static_cast<unsigned long long>(handshake_resyncs_),
                          static_cast<unsigned long long>(handshake_implausible_));
  }
  if (watchdog_) {
    text += printf_string("  watchdog         zero-torque process %d: fired %llu times on a stalled loop (%llu restarts)\n",
                          watchdog_->pid(), static_cast<unsigned long long>(watchdog_->fired()),
                          static_cast<unsigned long long>(watchdog_restarts_));
  }
  return text;
}

}  // namespace hapscene
