// `hapscene devices`: listing ports under a stand-in root laid out as /dev and /sys are
// (by-id links, ttyACM/ttyUSB nodes, sysfs USB attributes), and probing them with the
// handshake: a board answers with its firmware; a port that never answers receives
// nothing but HELLO frames.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "engine/devices/port_list.hpp"
#include "protocol/protocol.h"
#include "tests/cli/cli_support.hpp"
#include "tests/devices/pty_board.hpp"

using namespace hapscene;
namespace fs = std::filesystem;

namespace {

// A pseudo-terminal whose master only listens: every frame the host writes is decoded
// and its type kept.
class ListeningPty {
 public:
  ListeningPty() {
    master_ = posix_openpt(O_RDWR | O_NOCTTY);
    REQUIRE(master_ >= 0);
    REQUIRE(grantpt(master_) == 0);
    REQUIRE(unlockpt(master_) == 0);
    path_ = ptsname(master_);
    hs_decoder_init(&decoder_);
    thread_ = std::thread([this] {
      std::uint8_t buffer[256];
      while (!stop_.load()) {
        pollfd fd{master_, POLLIN, 0};
        if (poll(&fd, 1, 1) <= 0) continue;
        const ssize_t n = read(master_, buffer, sizeof buffer);
        for (ssize_t i = 0; i < n; ++i) {
          hs_decoder_push(&decoder_, buffer[i]);
          hs_frame frame;
          while (hs_decoder_poll(&decoder_, &frame)) {
            frames.fetch_add(1);
            if (frame.type != HS_TYPE_HELLO) others.fetch_add(1);
          }
        }
      }
    });
  }
  ~ListeningPty() {
    stop_.store(true);
    thread_.join();
    close(master_);
  }
  const std::string& path() const { return path_; }
  std::atomic<int> frames{0}, others{0};

 private:
  int master_{-1};
  std::string path_;
  hs_decoder decoder_{};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text << "\n";
}

// ROOT/dev/ttyACM0 -> the board's pty, ROOT/dev/ttyUSB0 -> the silent one, by-id links
// and sysfs entries as udev and the kernel make them.
fs::path make_root(const std::string& board_pty, const std::string& silent_pty) {
  const fs::path root = fs::temp_directory_path() / ("hapscene_devices_" + std::to_string(getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "dev/serial/by-id");
  fs::create_symlink(board_pty, root / "dev/ttyACM0");
  fs::create_symlink(silent_pty, root / "dev/ttyUSB0");
  fs::create_symlink("../../ttyACM0", root / "dev/serial/by-id/usb-Arduino__www.arduino.cc__0043_7573-if00");
  // ttyACM: the interface's parent is the USB device; ttyUSB: one level further down.
  const fs::path uno = root / "sys/devices/usb1/1-1";
  write_file(uno / "idVendor", "2341");
  write_file(uno / "idProduct", "0043");
  write_file(uno / "manufacturer", "Arduino (www.arduino.cc)");
  write_file(uno / "product", "Arduino Uno");
  write_file(uno / "serial", "7573");
  fs::create_directories(uno / "1-1:1.0");
  const fs::path ch340 = root / "sys/devices/usb1/1-2";
  write_file(ch340 / "idVendor", "1a86");
  write_file(ch340 / "idProduct", "7523");
  fs::create_directories(ch340 / "1-2:1.0/ttyUSB0");
  fs::create_directories(root / "sys/class/tty/ttyACM0");
  fs::create_directories(root / "sys/class/tty/ttyUSB0");
  fs::create_symlink("../../../devices/usb1/1-1/1-1:1.0", root / "sys/class/tty/ttyACM0/device");
  fs::create_symlink("../../../devices/usb1/1-2/1-2:1.0/ttyUSB0", root / "sys/class/tty/ttyUSB0/device");
  write_file(root / "dev/ttyS0", "");  // not a board's kind of port: not listed
  return root;
}

}  // namespace

TEST_CASE("devices: ports, their USB identity, and which answer the handshake" * doctest::test_suite("threaded")) {
  test::PtyBoard board;
  ListeningPty silent;
  const fs::path root = make_root(board.path(), silent.path());

  const std::vector<SerialPortEntry> ports = list_serial_ports(root.string());
  REQUIRE(ports.size() == 2);
  CHECK(ports[0].path == (root / "dev/ttyACM0").string());
  CHECK(ports[0].usb_vendor == "2341");
  CHECK(ports[0].usb_product == "0043");
  CHECK(ports[0].product == "Arduino Uno");
  CHECK(ports[0].serial == "7573");
  REQUIRE(ports[0].by_id.size() == 1);
  CHECK(ports[0].by_id[0].ends_with("/dev/serial/by-id/usb-Arduino__www.arduino.cc__0043_7573-if00"));
  CHECK(ports[1].path == (root / "dev/ttyUSB0").string());
  CHECK(ports[1].usb_vendor == "1a86");
  CHECK(usb_vendor_name(ports[1].usb_vendor) == "QinHeng (CH340)");
  CHECK(ports[1].by_id.empty());

  const std::vector<PortProbe> probes = probe_ports(ports, 1000000, 0.5);
  CHECK(probes[0].answered);
  CHECK(probes[0].firmware == "0.1.0");
  CHECK(probes[0].board == "Hapkit 3.0");
  CHECK_FALSE(probes[1].answered);
  CHECK(probes[1].failure.find("nothing") != std::string::npos);
  // The silent port heard HELLOs (every 100 ms) and nothing else.
  CHECK(silent.frames.load() >= 3);
  CHECK(silent.others.load() == 0);
  CHECK(board.commands.load() == 0);  // the board was only asked who it is

  // The command: a block per port, and how to run on the board found.
  setenv("HAPSCENE_DEVICES_ROOT", root.c_str(), 1);
  const test::CliOutcome table = test::run_cli("devices --timeout 0.5s");
  const test::CliOutcome json = test::run_cli("devices --json --no-probe");
  unsetenv("HAPSCENE_DEVICES_ROOT");
  CAPTURE(table.out);
  CHECK(table.exit_code == 0);
  CHECK(table.out.find("  usb       2341:0043 Arduino Uno (Arduino (www.arduino.cc)), serial 7573\n") != std::string::npos);
  CHECK(table.out.find("  answers   hapscene firmware 0.1.0, protocol 1, Hapkit 3.0\n") != std::string::npos);
  CHECK(table.out.find("  usb       1a86:7523 (QinHeng (CH340))\n") != std::string::npos);
  CHECK(table.out.find("  answers   no hapscene answer within 0.5 s: ") != std::string::npos);
  CHECK(table.out.find("run on it:  hapscene run ENV --device serial:" + (root / "dev/serial/by-id").string()) !=
        std::string::npos);
  CHECK(json.exit_code == 0);
  CHECK(json.out.find("\"usb_vendor\": \"2341\"") != std::string::npos);
  CHECK(json.out.find("\"answered\"") == std::string::npos);  // --no-probe opens nothing
  fs::remove_all(root);
}

TEST_CASE("devices: nothing plugged in, and bad options") {
  const fs::path root = fs::temp_directory_path() / ("hapscene_devices_empty_" + std::to_string(getpid()));
  fs::create_directories(root / "dev");
  CHECK(list_serial_ports(root.string()).empty());
  CHECK(list_serial_ports((root / "missing").string()).empty());
  fs::remove_all(root);
  CHECK(test::run_cli("devices --timeout 0").exit_code == 2);
  CHECK(test::run_cli("devices extra.json").exit_code == 2);
}
