// The permission messages end to end: hapscene run as an unprivileged user (setpriv, as
// root) on a serial port it may not open, and in real time without SCHED_FIFO.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <grp.h>
#include <sys/stat.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/cli/cli_support.hpp"

using namespace hapscene::test;

namespace {

// `hapscene ARGS` as the user nobody with no capabilities; exit code and stdout + stderr.
CliOutcome run_as_nobody(const std::string& args) {
  const auto out = std::filesystem::temp_directory_path() / ("hapscene_nobody_" + std::to_string(getpid()));
  const std::string command = "cd '" HAPSCENE_SOURCE_DIR "' && setpriv --reuid=65534 --regid=65534 --clear-groups '" +
                              std::string(HAPSCENE_BINARY) + "' " + args + " >'" + out.string() + "' 2>&1 </dev/null";
  const int status = std::system(command.c_str());
  CliOutcome outcome{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp_file(out), ""};
  std::filesystem::remove(out);
  return outcome;
}

bool can_drop_privileges() { return geteuid() == 0 && std::system("command -v setpriv >/dev/null 2>&1") == 0; }

}  // namespace

TEST_CASE("cli: a serial port the user may not open says how to join its group" * doctest::test_suite("threaded")) {
  if (!can_drop_privileges()) return;  // needs root to become another user
  // A pseudo-terminal's slave belongs to root (group tty, mode 620): nobody may not open it.
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  REQUIRE(master >= 0);
  REQUIRE(grantpt(master) == 0);
  REQUIRE(unlockpt(master) == 0);
  const std::string slave = ptsname(master);
  // The group that owns it (tty on most systems; a container's devpts may say root).
  struct stat info {};
  REQUIRE(stat(slave.c_str(), &info) == 0);
  const group* owner = getgrgid(info.st_gid);
  REQUIRE(owner != nullptr);
  const std::string group_name = owner->gr_name;
  const CliOutcome outcome = run_as_nobody("run environments/wall.json --device serial:" + slave + " --quiet");
  close(master);
  CAPTURE(outcome.out);
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.out.find("cannot open " + slave + ": Permission denied (the port belongs to the group \"" + group_name + "\"") !=
        std::string::npos);
  CHECK(outcome.out.find("sudo usermod -aG " + group_name + " nobody") != std::string::npos);
}

TEST_CASE("cli: a real-time run without SCHED_FIFO says how to allow it" * doctest::test_suite("threaded")) {
  if (!can_drop_privileges()) return;
  const CliOutcome outcome = run_as_nobody("run environments/spring.json --duration 50ms --quiet --hand hold");
  CAPTURE(outcome.out);
  CHECK(outcome.out.find("  scheduling       normal scheduling (SCHED_FIFO not permitted: Operation not permitted)") !=
        std::string::npos);
  CHECK(outcome.out.find("  to allow it      add \"nobody - rtprio 95\"") != std::string::npos);
  CHECK(outcome.out.find("setcap cap_sys_nice") != std::string::npos);
  // A privileged run asks for nothing.
  const CliOutcome root = run_cli("run environments/spring.json --duration 50ms --quiet --hand hold");
  CHECK(root.out.find("to allow it") == std::string::npos);
}
