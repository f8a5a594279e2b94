// `hapscene run --device haply:PATH` end to end: a hapscene process drives a fake board
// running Haply's stock firmware on a pseudo-terminal, renders, and leaves zero torque on
// the board however it ends: the end of the run, SIGTERM, and kill -9 (the watchdog).
#include <doctest/doctest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <thread>

#include "engine/devices/planar/simulated_planar.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/devices/pty_haply_board.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;
using namespace hapscene::test;

namespace {

// A spring 10 mm above the 2DIY v3's home: about 1 N there (after the soft start). At
// 100 Hz: these tests are about the device path, and a loop with 10 ms per tick does not
// fail on the stalls of a machine busy with builds (ten missed deadlines in a row).
constexpr const char* kSpringAboveHome = R"({"name": "pull", "device": "haply2diy_v3", "rate_hz": 100,
  "effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["19 mm", "100 mm"]}]})";

bool torque_on(const test::FakeHaplyBoard& b) { return b.torque_N_m[0] != 0.0f || b.torque_N_m[1] != 0.0f; }
bool torque_off(const test::FakeHaplyBoard& b) { return b.torque_N_m[0] == 0.0f && b.torque_N_m[1] == 0.0f; }

// The user's hand after the setup: from the reference pose (where the board presets its
// encoders, below the workspace) to the profile's home, turning the joints at most about
// 12 rad/s, as a hand would.
void move_to_home(PtyHaplyBoard& board) {
  CHECK(board.wait_for([](auto& b) { return b.setups >= 1 && b.torque_frames >= 3; }, 10000));
  const PlanarProfile v3 = load_planar_profile("haply2diy_v3", ".");
  const Vec2 q_rad = planar_joint_angles_at(v3, v3.home_m);
  const double step1_deg = (q_rad[0] * 180.0 / 3.141592653589793 - 168.0) / 100.0;  // joint 1: port 2
  const double step2_deg = (q_rad[1] * 180.0 / 3.141592653589793 - 12.0) / 100.0;   // joint 2: port 1
  for (int i = 0; i < 100; ++i) {
    board.with_board([&](auto& b) {
      b.turn(2, step1_deg);
      b.turn(1, step2_deg);
      return 0;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

// Starts `hapscene run ENV --device haply:PATH` for a long run; returns its pid.
pid_t start_run(const std::string& environment, const std::string& port) {
  const std::string device = "haply:" + port;  // made before the fork
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {

    // Between fork and exec only async-signal-safe calls (this process has threads).
    const int null_fd = open("/dev/null", O_WRONLY);
    if (null_fd < 0 || dup2(null_fd, 1) < 0 || dup2(null_fd, 2) < 0) _exit(126);
    execl(HAPSCENE_BINARY, HAPSCENE_BINARY, "run", environment.c_str(), "--device", device.c_str(), "--duration",
          "60s", "--no-reload", "--quiet", static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

}  // namespace

TEST_SUITE("threaded") {
TEST_CASE("haply run cli: a run renders on the board, reports the link, and ends at zero torque") {
  const test::ScratchFolder folder("haply_run_cli");
  const std::string env = folder.write("pull.json", kSpringAboveHome).string();
  PtyHaplyBoard board;
  std::thread hand([&] { move_to_home(board); });
  const CliOutcome out = run_cli("run '" + env + "' --device haply:" + board.path() + " --duration 1.5s --no-reload");
  hand.join();
  CAPTURE(out.out);
  CHECK(out.out.find("  haply link       ") != std::string::npos);
  CHECK(out.out.find("  watchdog         zero-torque process") != std::string::npos);
  // A clean run, unless this shared machine stalled the pseudo-terminal (its buffers are
  // flushed by a kernel worker at normal priority) or starved the fake board's thread:
  // then the run says so (a silent board, or ten missed deadlines) and fails, as it must.
  const bool stalled = out.out.find("FAULT            sustained overrun") != std::string::npos;
  if (stalled) {
    CHECK(out.exit_code == 1);
  } else if (out.out.find("; 0 resyncs;") != std::string::npos) {
    CHECK(out.exit_code == 0);
    CHECK(board.with_board([](auto& b) { return b.setups; }) >= 1);
  } else {
    CHECK(out.out.find("resyncs (silence ") != std::string::npos);
    CHECK(out.exit_code == 1);
  }
  CHECK(board.with_board([](auto& b) { return b.peak_torque_N_m; }) > 0.01f);  // it rendered
  CHECK(board.wait_for(torque_off, 2000));                                     // and stopped
}

TEST_CASE("haply run cli: device and scene must match, and the simulator's options are refused") {
  const test::ScratchFolder folder("haply_run_cli_refused");
  const std::string env = folder.write("pull.json", kSpringAboveHome).string();
  const CliOutcome no_path = run_cli("run '" + env + "' --device haply:");
  CHECK(no_path.exit_code == 2);
  CHECK(no_path.err.find("--device haply: needs a port path") != std::string::npos);
  const CliOutcome haplink = run_cli("run environments/planar/haplink_box_inside.json --device haply:/dev/null");
  CHECK(haplink.exit_code == 2);
  CHECK(haplink.err.find("profile \"haplink\", joint 1 is not a Haply-style joint") != std::string::npos);
  const CliOutcome one_dof = run_cli("run environments/wall.json --device haply:/dev/null");
  CHECK(one_dof.exit_code == 2);
  CHECK(one_dof.err.find("a Haply board drives a 2-DOF scene") != std::string::npos);
  const CliOutcome hand = run_cli("run '" + env + "' --device haply:/dev/null --hand circle");
  CHECK(hand.exit_code == 2);
  CHECK(hand.err.find("--hand: the simulated device's option") != std::string::npos);
  const CliOutcome sim_time = run_cli("run '" + env + "' --device haply:/dev/null --sim-time");
  CHECK(sim_time.exit_code == 2);
  CHECK(sim_time.err.find("runs in real time") != std::string::npos);
}

TEST_CASE("haply run cli: a stalled host (SIGSTOP) gets zero torque from the watchdog, then ramps in again") {
  const test::ScratchFolder folder("haply_run_cli_stall");
  const std::string env = folder.write("pull.json", kSpringAboveHome).string();
  PtyHaplyBoard board;
  const pid_t run = start_run(env, board.path());
  move_to_home(board);
  if (board.wait_for(torque_on, 10000)) {
    kill(run, SIGSTOP);
    CHECK(board.wait_for(torque_off, 3000));  // the stall bound is 100 ms
    kill(run, SIGCONT);
    // The host saw the watchdog fire (a restart) and renders again after its soft start.
    CHECK(board.wait_for(torque_on, 5000));
  } else {
    // (A run this shared machine stalls ends itself on its overruns, at zero torque.)
    int status = 0;
    CHECK(waitpid(run, &status, WNOHANG) == run);
  }
  kill(run, SIGKILL);
  waitpid(run, nullptr, 0);
  CHECK(board.wait_for(torque_off, 3000));
}

TEST_CASE("haply run cli: SIGTERM ends the run at zero torque, and so does kill -9 (the watchdog)") {
  const test::ScratchFolder folder("haply_run_cli_signals");
  const std::string env = folder.write("pull.json", kSpringAboveHome).string();
  for (const int signal : {SIGTERM, SIGKILL}) {
    CAPTURE(signal);
    PtyHaplyBoard board;
    const pid_t run = start_run(env, board.path());
    move_to_home(board);
    // (A run this shared machine stalls ends itself on its overruns, at zero torque.)
    if (!board.wait_for(torque_on, 10000)) {
      int status = 0;
      CHECK(waitpid(run, &status, WNOHANG) == run);
      CHECK(board.with_board(torque_off));
      continue;
    }
    kill(run, signal);
    int status = 0;
    waitpid(run, &status, 0);
    if (signal == SIGTERM) {
      CHECK(WIFEXITED(status));  // a clean end: the run stopped, zero force, the summary
    } else {
      CHECK(WIFSIGNALED(status));
    }
    // The board keeps its last torque on its own: hapscene or its watchdog took it off.
    CHECK(board.wait_for(torque_off, 3000));
  }
}
}
