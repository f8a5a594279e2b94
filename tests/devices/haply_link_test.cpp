// The host's side of the Haply protocol against a fake stock-firmware board on an
// in-memory wire, in simulated time: the setup, torques on the right ports, and every fault
// the protocol cannot frame away (wrong ids, short replies, garbage, silence, a board reset,
// an unplugged cable): each is detected, counted by reason, renders zero torque until the
// board answers again, and keeps the angles continuous.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "engine/devices/haply/haply_link.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "tests/devices/fake_haply_board.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {

constexpr std::int64_t kTick_ns = 1'000'000;
constexpr double kCount_deg = 360.0 / 4880.0;  // v3's encoder resolution

// A link to a fake v3 board, ticked at 1 kHz of simulated time.
struct Rig {
  test::FakeHaplyBoard board;
  test::FakeHaplyWire wire{&board};
  HaplySetup setup = haply_setup_for(load_planar_profile("haply2diy_v3", "."));
  std::int64_t now_ns{0};
  HaplyLink link{wire, setup, HaplyLinkConfig{}, 0};

  // One tick: poll, then send `torque` (N m per joint).
  void tick(const Vec2& torque_N_m = Vec2{}) {
    now_ns += kTick_ns;
    link.poll(now_ns);
    link.send(torque_N_m, now_ns);
  }
  void ticks(int n, const Vec2& torque_N_m = Vec2{}) {
    for (int i = 0; i < n; ++i) tick(torque_N_m);
  }
  // Ticks until running again (at most `limit`); how many it took.
  int until_running(int limit = 200, const Vec2& torque_N_m = Vec2{}) {
    for (int i = 1; i <= limit; ++i) {
      tick(torque_N_m);
      if (link.state() == HaplyLinkState::running && link.position_status() == PositionStatus::fresh) return i;
    }
    return -1;
  }
  std::uint64_t resyncs(HaplyResyncReason reason) const {
    return link.counters().by_reason[static_cast<std::size_t>(reason)];
  }
};

const Vec2 kTorque{{0.05, -0.03}};

// Equal up to one encoder count (the fake board reports whole counts).
bool within_a_count(double a_deg, double b_deg) { return std::fabs(a_deg - b_deg) <= kCount_deg * 1.0001; }

}  // namespace

TEST_CASE("haply link: setup, then torques on each joint's port and angles per joint") {
  Rig rig;
  CHECK(rig.board.setups == 1);
  CHECK(rig.link.position_status() == PositionStatus::unmeasured);
  // Nothing is trusted before the first reply, and nothing but zero torque goes out.
  const int ticks = rig.until_running();
  REQUIRE(ticks > 0);
  CHECK(ticks <= 8);  // the quiet time (5 ms) and two replies that agree
  CHECK(rig.link.take_restart());
  CHECK_FALSE(rig.link.take_restart());
  // At the reference pose the board reads its offsets: joint 1 168 deg (port 2), joint 2 12 deg.
  CHECK(within_a_count(rig.link.angles_deg()[0], 168.0));
  CHECK(within_a_count(rig.link.angles_deg()[1], 12.0));

  rig.ticks(3, kTorque);
  CHECK(rig.board.torque_N_m[1] == doctest::Approx(0.05));   // port 2: joint 1
  CHECK(rig.board.torque_N_m[0] == doctest::Approx(-0.03));  // port 1: joint 2
  rig.board.turn(2, 1.0);   // joint 1 turns a degree
  rig.board.turn(1, -0.5);  // joint 2 back half of one
  rig.ticks(2, kTorque);
  CHECK(within_a_count(rig.link.angles_deg()[0], 169.0));
  CHECK(within_a_count(rig.link.angles_deg()[1], 11.5));
  CHECK(rig.link.position_status() == PositionStatus::fresh);
  CHECK(rig.link.counters().resyncs == 0);
}

// Each fault: detected and named, zero torque at the board until the link is back, the
// angles continuous across, and a soft start asked for.
TEST_CASE("haply link: every desynchronisation is caught, zeroes the torque, and recovers") {
  struct Fault {
    const char* name;
    HaplyResyncReason reason;
    void (*inject)(Rig&);
  };
  const Fault faults[] = {
      {"a wrong id", HaplyResyncReason::wrong_id, [](Rig& r) { r.board.wrong_ids = 1; }},
      {"garbage before a reply", HaplyResyncReason::wrong_id,
       [](Rig& r) { r.board.garbage = {0x41, 0x42, 0x43}; }},
      {"a short reply, then nothing", HaplyResyncReason::short_reply, [](Rig& r) {
         r.board.short_replies = 1;
         r.board.mute_after_reply = true;
       }},
      {"a reply with a NaN angle", HaplyResyncReason::corrupt,
       [](Rig& r) { r.board.garbage = {0x05, 0x00, 0x00, 0xC0, 0x7F, 0x00, 0x00, 0x00, 0x00}; }},
      {"a board reset (counts back at their preset)", HaplyResyncReason::jump,
       [](Rig& r) { r.board.reset_counts(); }},
      {"silence", HaplyResyncReason::silence, [](Rig& r) { r.board.muted = true; }},
  };
  for (const Fault& fault : faults) {
    CAPTURE(std::string(fault.name));
    Rig rig;
    REQUIRE(rig.until_running() > 0);
    (void)rig.link.take_restart();
    // The arm away from its reference pose, with a torque on.
    for (int i = 0; i < 40; ++i) {
      rig.board.turn(2, -0.5);  // 8.7 rad/s
      rig.board.turn(1, 0.25);
      rig.tick(kTorque);
    }
    rig.tick(kTorque);  // the reply to a tick's frame is read at the next tick
    const Vec2 before = rig.link.angles_deg();
    CHECK(within_a_count(before[0], 168.0 - 20.0));
    CHECK(within_a_count(before[1], 12.0 + 10.0));
    CHECK(rig.link.counters().resyncs == 0);
    REQUIRE(rig.board.torque_N_m[1] != 0.0f);

    fault.inject(rig);
    int ticks_until_caught = 0;
    while (rig.link.counters().resyncs == 0 && ticks_until_caught < 200) {
      rig.tick(kTorque);
      ++ticks_until_caught;
    }
    CHECK(rig.resyncs(fault.reason) == 1);
    CHECK(rig.link.counters().resyncs == 1);
    // Zero torque at once, and no position to render from while resynchronising.
    CHECK(rig.board.torque_N_m[0] == 0.0f);
    CHECK(rig.board.torque_N_m[1] == 0.0f);
    CHECK(rig.link.position_status() == PositionStatus::unmeasured);
    CHECK(rig.board.setups == 2);

    rig.board.muted = false;
    const int back = rig.until_running(200, kTorque);
    REQUIRE(back > 0);
    CHECK(rig.link.take_restart());
    // Continuous: the correction carries the angles across the board's re-preset.
    CHECK(within_a_count(rig.link.angles_deg()[0], before[0]));
    CHECK(within_a_count(rig.link.angles_deg()[1], before[1]));
    rig.board.turn(2, 2.0);
    rig.ticks(2, kTorque);
    CHECK(within_a_count(rig.link.angles_deg()[0], before[0] + 2.0));
    CHECK(rig.board.torque_N_m[1] == doctest::Approx(0.05));
    CHECK(rig.link.counters().resyncs == 1);
    CHECK(rig.link.report(0).find(haply_resync_reason_name(fault.reason)) != std::string::npos);
  }
}

TEST_CASE("haply link: a short reply among good ones misaligns the stream, which is caught") {
  Rig rig;
  REQUIRE(rig.until_running() > 0);
  rig.ticks(5, kTorque);
  rig.board.short_replies = 1;
  rig.ticks(3, kTorque);
  // The next reply's id lands where an angle should be: caught as a wrong id at once.
  CHECK(rig.link.counters().resyncs == 1);
  CHECK(rig.resyncs(HaplyResyncReason::wrong_id) + rig.resyncs(HaplyResyncReason::jump) +
            rig.resyncs(HaplyResyncReason::corrupt) == 1);
  CHECK(rig.board.torque_N_m[0] == 0.0f);
  CHECK(rig.until_running(200, kTorque) > 0);
}

TEST_CASE("haply link: a stray byte during the setup runs it again rather than shifting a reply") {
  Rig rig;
  rig.ticks(4);
  rig.board.garbage = {0x05};  // an id-like byte ahead of the first reply
  const int ticks = rig.until_running();
  REQUIRE(ticks > 0);
  CHECK(rig.link.counters().setup_retries == 1);
  CHECK(rig.link.counters().resyncs == 0);
  CHECK(within_a_count(rig.link.angles_deg()[0], 168.0));
  CHECK(within_a_count(rig.link.angles_deg()[1], 12.0));
}

TEST_CASE("haply link: a burst of replies at once is judged reply by reply, not taken for a fault") {
  Rig rig;
  REQUIRE(rig.until_running() > 0);
  // Ten frames go out before the host reads again (a late tick; a USB adapter's batch).
  for (int i = 0; i < 10; ++i) {
    rig.board.turn(2, 0.1);
    rig.link.send(kTorque, rig.now_ns);
  }
  rig.tick(kTorque);
  CHECK(rig.link.counters().resyncs == 0);
  CHECK(rig.link.position_status() == PositionStatus::fresh);
  CHECK(within_a_count(rig.link.angles_deg()[0], 169.0));  // the newest of the burst
}

TEST_CASE("haply link: a port that takes frames in part still delivers them whole and in order") {
  Rig rig;
  REQUIRE(rig.until_running() > 0);
  // 7 bytes a write: every 10-byte torque frame is split, and the rest must go out first.
  const int resets_before = rig.board.resets;
  rig.wire.takes_at_most = 7;
  for (int i = 0; i < 20; ++i) rig.tick(Vec2{{0.01 * (i % 5), -0.02}});
  CHECK(rig.link.counters().partial_writes > 0);
  CHECK(rig.link.counters().resyncs == 0);
  CHECK(rig.board.resets == resets_before);  // no torque bytes read as a command
  CHECK(rig.board.torque_N_m[1] == doctest::Approx(0.04));  // the last frame: 0.01 * (19 % 5)
  CHECK(rig.board.torque_N_m[0] == doctest::Approx(-0.02));
  // A port that takes nothing: frames queue, then are dropped whole, never cut.
  rig.wire.takes_at_most = 0;
  for (int i = 0; i < 100; ++i) rig.link.send(kTorque, rig.now_ns);
  CHECK(rig.link.counters().frames_dropped > 0);
  rig.wire.takes_at_most = -1;
  const int frames_before = rig.board.torque_frames;
  rig.link.send(Vec2{{0.03, 0.03}}, rig.now_ns);
  CHECK(rig.board.torque_frames > frames_before);
  CHECK(rig.board.torque_N_m[1] == doctest::Approx(0.03));
}

TEST_CASE("haply link: a board that stays silent is retried, each time counted") {
  Rig rig;
  REQUIRE(rig.until_running() > 0);
  rig.board.muted = true;
  rig.ticks(200, kTorque);  // 200 ms: silence after 50 ms, again every 50 + 5 ms
  CHECK(rig.resyncs(HaplyResyncReason::silence) >= 3);
  CHECK(rig.link.position_status() == PositionStatus::unmeasured);
  CHECK(rig.board.torque_N_m[0] == 0.0f);
  CHECK(rig.board.torque_N_m[1] == 0.0f);
}

TEST_CASE("haply link: an unplugged cable is reopened and the board set up again") {
  Rig rig;
  REQUIRE(rig.until_running() > 0);
  rig.ticks(5, kTorque);
  rig.wire.unplugged = true;
  rig.tick(kTorque);
  CHECK(rig.link.state() == HaplyLinkState::vanished);
  CHECK(rig.resyncs(HaplyResyncReason::vanished) == 1);
  rig.ticks(300, kTorque);  // retried every 500 ms: not yet
  CHECK(rig.link.state() == HaplyLinkState::vanished);
  rig.wire.unplugged = false;
  const int setups_before = rig.board.setups;
  CHECK(rig.until_running(400, kTorque) > 0);
  CHECK(rig.board.setups == setups_before + 1);
  CHECK(rig.resyncs(HaplyResyncReason::vanished) == 1);
}

TEST_CASE("haply link: a reply late by a few ticks is stale, not a fault") {
  Rig rig;
  REQUIRE(rig.until_running() > 0);
  rig.board.muted = true;
  rig.ticks(7, kTorque);
  CHECK(rig.link.position_status() == PositionStatus::stale);
  CHECK(rig.link.counters().resyncs == 0);
  rig.board.muted = false;
  rig.ticks(2, kTorque);
  CHECK(rig.link.position_status() == PositionStatus::fresh);
  CHECK(rig.link.counters().resyncs == 0);
}

// Every reply is judged before a torque may follow from it, after a resync as at the
// start: a board that answers the setup with 3e17 deg, a NaN, or angles farther from its
// preset offsets than the arm can turn since the setup is set up again, never trusted.
// (Before, two such replies that agreed with each other became the angle correction, and
// the torques that followed were computed from a made-up pose.)
TEST_CASE("haply link: implausible angles after a resync are rejected, and no torque follows them") {
  struct Bad {
    const char* name;
    float deg;
    ReadingFault fault;
  };
  const Bad bads[] = {
      {"3e17 deg", 3e17f, ReadingFault::out_of_range},
      {"NaN", std::numeric_limits<float>::quiet_NaN(), ReadingFault::not_finite},
      // 68 deg (joint 1) and 88 deg (joint 2) from the preset a few ms after the setup:
      // far more than 60 rad/s allows.
      {"a jump too fast for the arm", 100.0f, ReadingFault::too_fast},
  };
  for (const Bad& bad : bads) {
    CAPTURE(std::string(bad.name));
    Rig rig;
    REQUIRE(rig.until_running() > 0);
    (void)rig.link.take_restart();
    for (int i = 0; i < 20; ++i) {
      rig.board.turn(2, -0.5);
      rig.tick(kTorque);
    }
    rig.tick(kTorque);  // the reply to a tick's frame is read at the next tick
    REQUIRE(rig.board.torque_since_reset > 0);
    const Vec2 before = rig.link.angles_deg();
    // A wrong id starts a resync; from then on the board answers with the bad angles.
    rig.board.wrong_ids = 1;
    rig.board.forced_replies = 1'000'000;
    rig.board.forced_deg = bad.deg;
    rig.ticks(300, kTorque);
    CHECK(rig.board.resets >= 2);
    CHECK(rig.board.torque_since_reset == 0);  // zero torque, and nothing else, since the resync
    CHECK(rig.link.state() == HaplyLinkState::configuring);
    CHECK(rig.link.position_status() == PositionStatus::unmeasured);
    CHECK(rig.link.counters().implausible >= 2);
    CHECK(rig.link.counters().first_implausible_fault == bad.fault);
    CHECK(rig.link.report(0).find("implausible") != std::string::npos);
    // The board answers sensibly again: running, the angles continuous, torque back.
    rig.board.forced_replies = 0;
    REQUIRE(rig.until_running(200, kTorque) > 0);
    CHECK(within_a_count(rig.link.angles_deg()[0], before[0]));
    CHECK(within_a_count(rig.link.angles_deg()[1], before[1]));
    rig.ticks(3, kTorque);
    CHECK(rig.board.torque_since_reset > 0);
  }
}

// While running too: each bad reply is counted as implausible (with the resync it causes).
TEST_CASE("haply link: an implausible reply while running is counted and resynchronises") {
  Rig rig;
  REQUIRE(rig.until_running() > 0);
  rig.ticks(5, kTorque);
  rig.board.forced_replies = 1;
  rig.board.forced_deg = 3e17f;
  rig.ticks(3, kTorque);
  CHECK(rig.link.counters().implausible == 1);
  CHECK(rig.link.counters().first_implausible_fault == ReadingFault::out_of_range);
  CHECK(rig.resyncs(HaplyResyncReason::jump) == 1);
  CHECK(rig.board.torque_since_reset == 0);
  CHECK(rig.until_running(200, kTorque) > 0);
}

}  // namespace HAPSCENE_TEST_FILE
