// The host's protocol session against a scripted board: handshake, commands and states,
// latency, garbage and lost frames, silence, board resets and a vanished port.
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "engine/base/format.hpp"
#include "engine/devices/board_link.hpp"
#include "engine/devices/board_report.hpp"
#include "tests/devices/fake_board.hpp"

using namespace hapscene;

namespace {

using test::LoopbackLink;

constexpr std::int64_t kTick_ns = 1'000'000;

// One tick as a device runs it: read, then send the command.
void tick(BoardLink* link, std::int64_t* now_ns, MotorCommand command = {0.5, true}) {
  link->poll(*now_ns);
  link->send(command, *now_ns);
  *now_ns += kTick_ns;
}

}  // namespace

TEST_CASE("board link: handshake, then one command and one state per tick") {
  LoopbackLink wire;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  CHECK(link.state() == LinkState::handshaking);
  tick(&link, &now_ns);  // HELLO out
  tick(&link, &now_ns);  // HELLO_REPLY in: running; first COMMAND out
  CHECK(link.state() == LinkState::running);
  CHECK(link.identified());
  CHECK(link.identity().sample_rate_hz == 5000);
  CHECK(link.take_restart());
  CHECK_FALSE(link.take_restart());
  for (int i = 0; i < 10; ++i) tick(&link, &now_ns);
  CHECK(wire.board.commands == 11);
  CHECK(wire.board.last_command.duty == 128);
  CHECK(wire.board.last_command.flags == (HS_COMMAND_ENABLE | HS_COMMAND_DIRECTION_HIGH));
  CHECK(link.counts() == 500);
  // Each state arrives one tick after its command.
  CHECK(link.round_trip_ns().count() == 10);
  CHECK(link.round_trip_ns().max_ns() == kTick_ns);
  CHECK(link.counters().seq_gaps == 0);
  // Zero force is sent with the motor disabled.
  tick(&link, &now_ns, MotorCommand{0.0, false});
  CHECK(wire.board.last_command.duty == 0);
  CHECK(wire.board.last_command.flags == 0);
}

TEST_CASE("board link: garbage and a corrupt frame are skipped, a lost frame counted") {
  LoopbackLink wire;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  for (int i = 0; i < 3; ++i) tick(&link, &now_ns);
  // Garbage ahead of the next answer.
  wire.to_host.insert(wire.to_host.begin(), {0x00, 0xA5, 0x77, 0xA5});
  wire.board.unwrapped_counts = 510;
  tick(&link, &now_ns);
  tick(&link, &now_ns);
  CHECK(link.counts() == 510);
  CHECK(link.decoder().bytes_skipped >= 4);
  // A corrupt answer: dropped (the tick keeps the last position), then a gap is seen.
  wire.board.unwrapped_counts = 520;
  tick(&link, &now_ns);  // the answer to this tick's command is now queued
  wire.to_host[6] ^= 0x40;
  tick(&link, &now_ns);
  CHECK(link.counts() == 510);
  CHECK(link.decoder().crc_errors >= 1);
  tick(&link, &now_ns);
  CHECK(link.counts() == 520);
  CHECK(link.counters().seq_gaps == 1);
  CHECK(link.counters().stale_reads >= 1);
}

TEST_CASE("board link: a silent board gets zero force, then HELLOs until it answers") {
  LoopbackLink wire;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  link.take_restart();
  wire.board.muted = true;
  for (int i = 0; i < 60; ++i) tick(&link, &now_ns);
  CHECK(link.state() == LinkState::silent);
  // Events: connected, position stale (after 5 ms), silent (after 50 ms).
  REQUIRE(link.event_count() == 3);
  CHECK(link.event(1).kind == LinkEventKind::position_stale);
  CHECK(link.event(2).kind == LinkEventKind::silent);
  CHECK(link.event(2).t_ns > 50 * kTick_ns);
  // The last command the board saw while muted cannot be checked (it was muted), so
  // unmute and check the motor-off command and the HELLOs go out and bring it back.
  wire.board.muted = false;
  const int hellos_before = wire.board.hellos;
  for (int i = 0; i < 120; ++i) tick(&link, &now_ns);
  CHECK(wire.board.hellos > hellos_before);
  CHECK(link.state() == LinkState::running);
  CHECK(link.take_restart());
}

TEST_CASE("board link: a reset board is re-armed and the position stays continuous") {
  LoopbackLink wire;
  BoardLinkConfig config;
  config.span_counts = 922;
  BoardLink link(wire, config);
  std::int64_t now_ns = 0;
  wire.board.unwrapped_counts = 1400;  // one period and a bit above home
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  CHECK(link.counts() == 1400);
  // The board restarts counting from its raw reading: 1400 - 922 = 478 (+2 of motion).
  wire.board.reset(480);
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  CHECK(link.state() == LinkState::running);
  CHECK(link.counts() == 1402);
  bool saw_reset = false;
  for (std::size_t i = 0; i < link.event_count(); ++i) {
    saw_reset |= link.event(i).kind == LinkEventKind::board_reset;
  }
  CHECK(saw_reset);
}

TEST_CASE("board link: a vanished port is reopened now and then, without blocking") {
  LoopbackLink wire;
  BoardLinkConfig config;
  config.reopen_retry_ns = 100 * kTick_ns;
  BoardLink link(wire, config);
  std::int64_t now_ns = 0;
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  wire.gone = true;
  for (int i = 0; i < 250; ++i) tick(&link, &now_ns);
  CHECK(link.state() == LinkState::vanished);
  CHECK(wire.reopen_attempts == 2);
  wire.can_reopen = true;
  for (int i = 0; i < 105; ++i) tick(&link, &now_ns);
  CHECK(link.state() == LinkState::running);
  const std::string report = board_report(link, 0);
  CHECK(report.find("vanished") != std::string::npos);
  CHECK(report.find("port reopened") != std::string::npos);
  CHECK(report.find("round trip") != std::string::npos);
}

// The link's health counters are printed, so a fault they count is never hidden.
TEST_CASE("board link: the report prints unanswered commands, partial writes and the board's status flags") {
  LoopbackLink wire;
  BoardLink link(wire, BoardLinkConfig{});
  std::int64_t now_ns = 0;
  for (int i = 0; i < 5; ++i) tick(&link, &now_ns);
  CHECK(board_report(link, 0).find("link health      0 commands unanswered, 0 frames not sent whole; "
                                   "states said command timeout 0, duty limited 0") != std::string::npos);
  // The board says its timeout fired and it limited the duty, in every STATE.
  wire.board.extra_status = HS_STATUS_TIMED_OUT | HS_STATUS_DUTY_LIMITED;
  for (int i = 0; i < 3; ++i) tick(&link, &now_ns);
  CHECK(link.counters().timeouts_reported >= 2);
  CHECK(link.counters().duty_limited == link.counters().timeouts_reported);
  wire.board.extra_status = 0;
  // The board stays alive but answers no COMMAND: those go unanswered (counted when
  // their sequence number comes round again).
  wire.board.states_muted = true;
  for (int i = 0; i < 300; ++i) tick(&link, &now_ns);
  CHECK(link.counters().unanswered > 0);
  wire.board.states_muted = false;
  // The port takes frames short (all but the last byte).
  wire.short_writes = true;
  for (int i = 0; i < 3; ++i) tick(&link, &now_ns);
  CHECK(link.counters().frames_dropped_tx >= 3);
  const std::string report = board_report(link, 0);
  CHECK(report.find(printf_string("%llu commands unanswered, %llu frames not sent whole; states said command "
                                  "timeout %llu, duty limited %llu",
                                  static_cast<unsigned long long>(link.counters().unanswered),
                                  static_cast<unsigned long long>(link.counters().frames_dropped_tx),
                                  static_cast<unsigned long long>(link.counters().timeouts_reported),
                                  static_cast<unsigned long long>(link.counters().duty_limited))) !=
        std::string::npos);
}
