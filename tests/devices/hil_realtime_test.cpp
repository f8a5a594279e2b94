// Firmware-in-the-loop in real time (`hapscene run ENV --device hil`): the board's world
// (its process running the firmware, the plant) keeps its own pace on a thread beside the
// loop (PacedWorld), as a real board does beside its host, and shares the loop's real-time
// scheduling (RealtimeGuard). The loop never waits for the simulated CPU: its deadlines are
// its own, a board that falls behind is seen through the link as a real one would be, and
// only the loop's own overruns fault.
#include <doctest/doctest.h>

#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <string>

#include "engine/devices/open_device.hpp"
#include "tests/support.hpp"

#if HAPSCENE_HAVE_HIL
#include "engine/devices/hil/hil_hapkit.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/runner.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {

HilConfig hil_config() {
  HilConfig config;
  config.firmware_elf = default_firmware_elf();
  return config;
}

bool fifo_granted(const RunSummary& summary) { return summary.realtime_note.starts_with("SCHED_FIFO"); }

void sleep_ms(long ms) {
  timespec duration{ms / 1000, (ms % 1000) * 1'000'000};
  while (nanosleep(&duration, &duration) != 0) {
  }
}

// The loop's own work overruns: from tick `from` on, each tick's observer burns `burn`.
class BurnFrom final : public TickObserver {
 public:
  BurnFrom(std::uint64_t from, std::chrono::microseconds burn) : from_(from), burn_(burn) {}
  void on_tick(const TickState& s) noexcept override {
    if (s.tick < from_) return;
    const auto until = std::chrono::steady_clock::now() + burn_;
    while (std::chrono::steady_clock::now() < until) {
    }
  }

 private:
  std::uint64_t from_;
  std::chrono::microseconds burn_;
};

}  // namespace

TEST_CASE("hil real time: the lab wall on the real firmware runs its seconds, the board beside the loop" *
          doctest::test_suite("threaded")) {
  // As `hapscene run environments/wall.json --device hil`: three runs of 1 s. When the loop
  // ran the board inside its tick, such runs ended on `frequent overruns` in 5 of 5 on an
  // idle 2-core machine (the board's 0.5 ms a period, 100 misses a second).
  const Scene scene = load_environment_file("environments/wall.json");
  for (int run = 0; run < 3; ++run) {
    HilHapkit hil(scene.device, hil_config());
    const RunSummary summary =
        run_scene(scene, hil, RunOptions{.duration_s = 1.0, .pacing = Pacing::real_time}, nullptr);
    INFO("run " << run << ": " << summary.realtime_note << "; " << summary.deadline_misses << " misses, "
                << summary.stall_misses << " stalls\n" << hil.report());
    CHECK_FALSE(hil.lost());
    CHECK(summary.simulation_misses == 0);  // the loop never waited for the board
    CHECK(hil.report().find("world pace       ") != std::string::npos);
    if (fifo_granted(summary)) {
      CHECK(summary.realtime_note.find("the simulated world at nice -20 (2 processes and threads)") != std::string::npos);
      CHECK_FALSE(summary.overrun_fault);
      CHECK(summary.ticks == 1000);
    } else {  // no real-time priority here: nothing to promise under load
      MESSAGE("SCHED_FIFO not permitted: the loop's pace is not checked (" << summary.realtime_note << ")");
    }
    // The board kept pace (within the firmware's 20 ms command timeout) and answered: the
    // handle's STATEs reached the host, no fault. A build that slows the world's own thread
    // (ThreadSanitizer's, several times) can leave it too far behind to keep the board's
    // timing: the summary says so, and the link is not judged then.
    if (hil.world().most_behind_ns() > 20'000'000) {
      MESSAGE("the simulated board fell " << static_cast<double>(hil.world().most_behind_ns()) * 1e-6 << " ms behind real time: its link is not judged");
      continue;
    }
    CHECK_FALSE(hil.fault_seen());
    CHECK(hil.link().counters().states_received > 100);
  }
}

TEST_CASE("hil real time: a board process stopped for 25 ms falls behind, the loop stays on time" *
          doctest::test_suite("threaded")) {
  // Another process stops the board process (SIGSTOP) 100 ms into a 0.4 s run for 25 ms.
  // The loop does not wait for it: the host sees a board that stopped answering (its
  // position goes stale), as with a real board, and the world catches up afterwards.
  const Scene scene = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 200}]})");
  HilHapkit hil(scene.device, hil_config());
  const pid_t board = hil.board().process_id();
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {  // only async-signal-safe calls here
    sleep_ms(100);
    kill(board, SIGSTOP);
    sleep_ms(25);
    kill(board, SIGCONT);
    _exit(0);
  }
  const RunSummary summary =
      run_scene(scene, hil, RunOptions{.duration_s = 0.4, .pacing = Pacing::real_time}, nullptr);
  int status = 0;
  waitpid(child, &status, 0);
  INFO(summary.realtime_note << "; " << summary.deadline_misses << " misses\n" << hil.report());
  CHECK_FALSE(hil.lost());
  CHECK_FALSE(summary.overrun_fault);
  CHECK(summary.simulation_misses == 0);
  CHECK(summary.ticks == 400);  // ran on to the end
  // The world fell at least 20 ms behind and the host saw the silence: ticks without a new
  // STATE, a stale position (force ramped out), then STATEs again.
  CHECK(hil.world().most_behind_ns() >= 20'000'000);
  CHECK(hil.link().counters().stale_reads >= 15);
  CHECK(hil.link().events_of(LinkEventKind::position_stale) >= 1);
  CHECK(hil.link().counters().states_received > 100);
}

TEST_CASE("hil real time: the loop's own overrun still faults as a sustained overrun" *
          doctest::test_suite("threaded")) {
  // From tick 50 on every tick's own work takes 3 periods: a streak of 10 within 4 ticks.
  const Scene scene = test::scene_from(R"({"effects": [{"type": "spring", "stiffness": 200}]})");
  HilHapkit hil(scene.device, hil_config());
  BurnFrom burn(50, std::chrono::microseconds(3000));
  const RunSummary summary =
      run_scene(scene, hil, RunOptions{.duration_s = 0.5, .pacing = Pacing::real_time}, &burn);
  CHECK(summary.overrun_fault);
  CHECK(summary.overrun_fault_kind == OverrunFault::streak);
  CHECK(summary.ticks >= 50);
  CHECK(summary.ticks < 60);
}

#endif  // HAPSCENE_HAVE_HIL

}  // namespace HAPSCENE_TEST_FILE
