// The link never hands the loop a position it cannot trust: none before the first STATE
// (after every connection), stale ones ramp force out, and impossible readings (out of
// range, overflowing, or farther than the handle can move) are faults, not positions.
// Also: a failed handshake says what the board answered.
#include <doctest/doctest.h>

#include <climits>
#include <cmath>
#include <string>

#include "engine/devices/board_link.hpp"
#include "engine/devices/board_report.hpp"
#include "engine/devices/profile.hpp"
#include "engine/run/runner.hpp"
#include "tests/devices/fake_board.hpp"
#include "tests/support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;
using test::LoopbackLink;

namespace {

constexpr std::int64_t kTick_ns = 1'000'000;

void tick(BoardLink* link, std::int64_t* now_ns, MotorCommand command = {0.5, true}) {
  link->poll(*now_ns);
  link->send(command, *now_ns);
  *now_ns += kTick_ns;
}

bool has_event(const BoardLink& link, LinkEventKind kind) {
  for (std::size_t i = 0; i < link.event_count(); ++i) {
    if (link.event(i).kind == kind) return true;
  }
  return false;
}

// A board on a loopback wire as the loop sees it, in simulated time.
class LoopbackDevice final : public Device {
 public:
  LoopbackDevice() : link(wire, BoardLinkConfig{}) {}
  std::int32_t read() noexcept override {
    link.poll(now_ns);
    return link.counts();
  }
  void write(const MotorCommand& command) noexcept override {
    link.send(command, now_ns);
    if (command.duty > 0.0) ++driven_ticks;
  }
  void advance(double dt_s) noexcept override { now_ns += static_cast<std::int64_t>(dt_s * 1e9); }
  bool take_restart() noexcept override { return link.take_restart(); }
  PositionStatus position_status() const noexcept override { return link.position_status(); }
  bool fault_seen() const noexcept override { return link.fault_seen(); }

  LoopbackLink wire;
  BoardLink link;
  std::int64_t now_ns{};
  int driven_ticks{};
};

// A spring pulling hard wherever the handle is near 0: any position gives force.
const char* kSpring = R"({"effects": [{"type": "spring", "stiffness": "2000 N/m", "center": "-50 mm"}]})";

}  // namespace

TEST_CASE("board link: no position before the first STATE, and none from a board that never sends one") {
  LoopbackLink wire;
  wire.board.states_muted = true;  // answers every COMMAND, but with STATS
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  for (int i = 0; i < 200; ++i) tick(&link, &now_ns);
  CHECK(link.state() == LinkState::running);  // the link stays alive ...
  CHECK(link.position_status() == PositionStatus::unmeasured);  // ... with no position
  CHECK(link.counters().unmeasured_polls >= 198);
  CHECK(has_event(link, LinkEventKind::no_position));
  CHECK(link.fault_seen());
  const std::string report = board_report(link, 0);
  CHECK(report.find("no position from the board") != std::string::npos);
  // The board starts answering: the position is fresh from its first STATE on.
  wire.board.states_muted = false;
  tick(&link, &now_ns);
  tick(&link, &now_ns);
  CHECK(link.position_status() == PositionStatus::fresh);
  CHECK(link.counts() == 500);
}

TEST_CASE("run: a board that answers the handshake but never sends a STATE is never driven") {
  const Scene scene = test::scene_from(kSpring);
  LoopbackDevice device;
  device.wire.board.states_muted = true;
  RunOptions options{.duration_s = 0.5, .pacing = Pacing::simulated_time};
  const RunSummary summary = run_scene(scene, device, options, nullptr);
  CHECK(device.link.state() == LinkState::running);
  CHECK(summary.max_abs_requested_N > 1.0);  // the scene asks for force at the default position
  CHECK(summary.max_abs_output_N == 0.0);     // none commanded
  CHECK(device.driven_ticks == 0);
  CHECK(summary.safety.position_hold_ticks == summary.ticks);
  CHECK(device.fault_seen());
}

TEST_CASE("run: force waits for the first STATE, ramps out when STATEs stop and back in when they return") {
  Scene scene = test::scene_from(kSpring);
  scene.safety.soft_start_s = 0.02;  // 20 ticks to ramp, either way
  finalise_safety(scene.period_s, &scene.safety);
  LoopbackDevice device;
  RunOptions options{.duration_s = 0.3, .pacing = Pacing::simulated_time};
  struct Watch final : TickObserver {
    LoopbackDevice* device{};
    std::vector<double> output_N;
    void on_tick(const TickState& s) noexcept override {
      output_N.push_back(s.output_N);
      // From tick 100 to 199 the board answers without a position.
      device->wire.board.states_muted = output_N.size() >= 100 && output_N.size() < 200;
    }
  } watch;
  watch.device = &device;
  watch.output_N.reserve(400);
  const RunSummary summary = run_scene(scene, device, options, &watch);
  REQUIRE(watch.output_N.size() == 300);
  // The handshake completes on tick 1; the first STATE answers tick 1's COMMAND.
  CHECK(watch.output_N[0] == 0.0);
  CHECK(watch.output_N[1] == 0.0);
  const double full_N = watch.output_N[99];
  CHECK(std::abs(full_N) > 1.0);
  // STATEs stop after tick 99: within the age bound (5 ms) the force holds, then ramps
  // out at the soft-start rate and stays at zero.
  CHECK(watch.output_N[103] == full_N);
  CHECK(std::abs(watch.output_N[110]) < std::abs(full_N));
  CHECK(std::abs(watch.output_N[110]) > 0.0);
  CHECK(watch.output_N[199] == 0.0);
  // STATEs return: ramped back in.
  CHECK(std::abs(watch.output_N[220]) > 0.0);
  CHECK(std::abs(watch.output_N[220]) < std::abs(full_N));
  CHECK(watch.output_N[299] == full_N);
  CHECK(has_event(device.link, LinkEventKind::position_stale));
  CHECK(device.link.counters().stale_polls > 80);
  CHECK(summary.safety.position_hold_ticks > 80);
  CHECK_FALSE(device.fault_seen());  // stale is not a fault: the board was alive
}

TEST_CASE("board link: absurd counts after a board reset are a fault, not a position") {
  LoopbackLink wire;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  wire.board.unwrapped_counts = 1400;
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  REQUIRE(link.counts() == 1400);
  // The board resets and reports INT32_MIN: rejected, the position stays, no force.
  wire.board.reset(INT32_MIN);
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  CHECK(link.state() == LinkState::running);
  CHECK(link.counts() == 1400);
  CHECK(link.position_status() == PositionStatus::implausible);
  CHECK(link.counters().implausible_states >= 1);
  CHECK(has_event(link, LinkEventKind::implausible_state));
  CHECK(link.fault_seen());
  // Sane readings again: realigned to the nearest period, and fresh.
  wire.board.unwrapped_counts = 480;
  for (int i = 0; i < 3; ++i) tick(&link, &now_ns);
  CHECK(link.position_status() == PositionStatus::fresh);
  CHECK(link.counts() == 1402);
}

TEST_CASE("board link: every out-of-range or impossible reading is rejected") {
  struct Case {
    const char* what;
    std::int32_t unwrapped;
    int raw;  // -1: consistent with unwrapped
  };
  const Case cases[] = {
      {"INT32_MAX", INT32_MAX, -1},
      {"INT32_MIN", INT32_MIN, -1},
      {"beyond 64 periods", 64 * 922 + 1, -1},
      {"raw beyond 10 bits", 510, 1024},
      {"a whole period away 1 ms later", 500 + 922, -1},
      {"600 counts (8 mm) away 1 ms later", 1100, -1},
  };
  for (const Case& c : cases) {
    CAPTURE(c.what);
    LoopbackLink wire;
    BoardLink link(wire, BoardLinkConfig{});
    std::int64_t now_ns = 0;
    for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
    REQUIRE(link.counts() == 500);
    wire.board.unwrapped_counts = c.unwrapped;
    wire.board.raw_counts_override = c.raw;
    tick(&link, &now_ns);
    tick(&link, &now_ns);
    CHECK(link.counts() == 500);
    CHECK(link.position_status() == PositionStatus::implausible);
    CHECK(link.counters().implausible_states >= 1);
  }
  // Fast but possible motion (100 counts, 1.3 mm in 1 ms) is a position.
  LoopbackLink wire;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  wire.board.unwrapped_counts = 600;
  tick(&link, &now_ns);
  tick(&link, &now_ns);
  CHECK(link.counts() == 600);
  CHECK(link.position_status() == PositionStatus::fresh);
  CHECK_FALSE(link.fault_seen());
}

TEST_CASE("board link: the speed bound follows the profile's counts") {
  const DeviceProfile profile = load_device_profile("hapkit3", ".");
  const BoardLinkConfig config = link_config_for(BoardLinkConfig{}, profile);
  const double m_per_count = std::abs(counts_to_position_m(profile, 1.0) - counts_to_position_m(profile, 0.0));
  CHECK(config.max_speed_counts_per_s * m_per_count == doctest::Approx(kMaxHandleSpeed_m_per_s));
}

TEST_CASE("board link: a board speaking another protocol version is named with its version and identity") {
  LoopbackLink wire;
  wire.board.protocol_version = 7;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  for (int i = 0; i < 20; ++i) tick(&link, &now_ns);
  CHECK(link.state() != LinkState::running);
  const std::string why = handshake_failure(link);
  CHECK(why.find("protocol version 7") != std::string::npos);
  CHECK(why.find("this host speaks 1") != std::string::npos);
  CHECK(why.find("firmware 0.1.0") != std::string::npos);
  CHECK(why.find("1E 95 0F") != std::string::npos);
  CHECK(has_event(link, LinkEventKind::refused_version));
}

TEST_CASE("board link: a failed handshake says what arrived: nothing, garbage or other frames") {
  {
    LoopbackLink wire;
    wire.board.muted = true;
    BoardLink link(wire, BoardLinkConfig{});
    std::int64_t now_ns = 0;
    for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
    CHECK(handshake_failure(link) == "no answer (nothing received)");
    // Garbage (a wrong baud rate looks like this).
    wire.to_host = {0x13, 0x77, 0xA5, 0x00, 0x42, 0x99, 0x01};
    tick(&link, &now_ns);
    CHECK(handshake_failure(link).find("bytes skipped") != std::string::npos);
  }
  {
    // A board that refuses the HELLO's version without saying its own.
    LoopbackLink wire;
    wire.board.muted = true;
    BoardLink link(wire, BoardLinkConfig{});
    std::int64_t now_ns = 0;
    const std::uint8_t refused[2] = {HS_TYPE_HELLO, HS_REFUSED_VERSION};
    std::uint8_t frame[HS_MAX_FRAME];
    const std::uint8_t size = hs_encode_frame(HS_TYPE_REFUSED, 0, refused, 2, frame);
    wire.to_host.assign(frame, frame + size);
    tick(&link, &now_ns);
    CHECK(handshake_failure(link).find("refused protocol version 1") != std::string::npos);
  }
  {
    // Valid frames of another kind.
    LoopbackLink wire;
    wire.board.muted = true;
    BoardLink link(wire, BoardLinkConfig{});
    std::int64_t now_ns = 0;
    std::uint8_t stats[HS_STATS_SIZE]{};
    std::uint8_t frame[HS_MAX_FRAME];
    const std::uint8_t size = hs_encode_frame(HS_TYPE_STATS, 0, stats, HS_STATS_SIZE, frame);
    wire.to_host.assign(frame, frame + size);
    tick(&link, &now_ns);
    CHECK(handshake_failure(link).find("1 valid frames (the last of type 0x83) but no HELLO_REPLY") !=
          std::string::npos);
  }
}

TEST_CASE("board link: a loop that starts long after the handshake is not a board without a position") {
  LoopbackLink wire;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  // The handshake, as a device's constructor runs it (HELLOs only, no COMMAND).
  for (int i = 0; i < 3 && link.state() != LinkState::running; ++i) {
    link.send(MotorCommand{}, now_ns);
    link.poll(now_ns);
    now_ns += kTick_ns;
  }
  REQUIRE(link.state() == LinkState::running);
  now_ns += 200 * kTick_ns;  // loading, other scenes ...
  for (int i = 0; i < 10; ++i) tick(&link, &now_ns);
  CHECK(link.position_status() == PositionStatus::fresh);
  CHECK_FALSE(has_event(link, LinkEventKind::no_position));
  CHECK_FALSE(link.fault_seen());
}

// After a board reset the position is realigned to the last one's sensor period, and then
// judged like any reading: a step farther than the handle can move since the last good
// STATE is rejected (before, a realigned reading was taken whatever its step).
TEST_CASE("board link: a realigned reading after a reset is judged for speed too") {
  LoopbackLink wire;
  BoardLinkConfig config;
  config.max_speed_counts_per_s = 1000.0;  // 1 count a ms: 400 counts need 0.4 s
  BoardLink link(wire, config);
  std::int64_t now_ns = 0;
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  REQUIRE(link.counts() == 500);
  wire.board.reset(900);
  for (int i = 0; i < 10; ++i) tick(&link, &now_ns);
  CHECK(link.events_of(LinkEventKind::board_reset) == 1);
  CHECK(link.state() == LinkState::running);
  CHECK(link.counts() == 500);
  CHECK(link.position_status() == PositionStatus::implausible);
  CHECK(link.counters().implausible_states >= 1);
  CHECK(link.fault_seen());
  // Where the handle was: plausible again.
  wire.board.unwrapped_counts = 505;
  for (int i = 0; i < 3; ++i) tick(&link, &now_ns);
  CHECK(link.position_status() == PositionStatus::fresh);
  CHECK(link.counts() == 505);
}

}  // namespace HAPSCENE_TEST_FILE
