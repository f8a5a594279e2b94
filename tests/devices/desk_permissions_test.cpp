// What a user is told when the system refuses the serial port or real-time scheduling:
// the cause and the fix, not just the errno text.
#include <doctest/doctest.h>

#include <cerrno>
#include <string>

#include "engine/devices/serial_port.hpp"
#include "engine/run/realtime.hpp"

using namespace hapscene;

TEST_CASE("permissions: a port that may not be opened names its group and the usermod command") {
  // /dev/null belongs to root's group: the message names the group that owns the path.
  const std::string denied = serial_open_failure("/dev/null", EACCES);
  CHECK(denied.starts_with("Permission denied (the port belongs to the group \"root\""));
  CHECK(denied.find("sudo usermod -aG root ") != std::string::npos);
  CHECK(denied.find("log out and in again") != std::string::npos);
  // A path that cannot be looked at: dialout, the group of serial adapters on Debian.
  CHECK(serial_open_failure("/nonexistent/ttyACM9", EACCES).find("sudo usermod -aG dialout ") != std::string::npos);
  CHECK(serial_open_failure("/dev/ttyACM9", ENOENT).find("`hapscene devices` lists the ports") != std::string::npos);
  CHECK(serial_open_failure("/dev/ttyACM0", EBUSY).find("another program holds the port") != std::string::npos);
  CHECK(serial_open_failure("/dev/ttyACM0", EIO) == "Input/output error");
}

TEST_CASE("permissions: refused real-time scheduling says how to allow it and what it costs") {
  const std::string both = realtime_permission_hint(true, true, "/usr/bin/hapscene", "ada");
  CHECK(both.find("\"ada - rtprio 95\" and \"ada - memlock unlimited\" to /etc/security/limits.d/hapscene.conf") !=
        std::string::npos);
  CHECK(both.find("sudo setcap cap_sys_nice,cap_ipc_lock+ep /usr/bin/hapscene") != std::string::npos);
  CHECK(both.find("other processes can preempt the loop") != std::string::npos);
  const std::string lock_only = realtime_permission_hint(false, true, "hapscene", "ada");
  CHECK(lock_only.find("rtprio") == std::string::npos);
  CHECK(lock_only.find("setcap cap_ipc_lock+ep") != std::string::npos);
  CHECK(realtime_permission_hint(false, false, "hapscene", "ada").empty());
}
