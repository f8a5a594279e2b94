// Two Hapkit boards as one 2-DOF device: a profile's board_serials (the boards' USB serial
// numbers) against the boards on the two paths, read from sysfs under a stand-in root laid
// out as /dev and /sys are, so swapped cables are caught before any port opens.
#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/devices/planar/hapkit_pair.hpp"
#include "engine/devices/planar/planar_profile.hpp"

using namespace hapscene;
namespace fs = std::filesystem;

namespace {

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text << "\n";
}

// ROOT/dev/ttyACM0 (USB serial A1), ttyACM1 (B2), ttyUSB0 (a CH340 without a serial
// number), by-id links for the first two.
fs::path make_root() {
  const fs::path root = fs::temp_directory_path() / ("hapscene_board_identity_" + std::to_string(getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "dev/serial/by-id");
  for (const std::string name : {"ttyACM0", "ttyACM1", "ttyUSB0"}) write_file(root / "dev" / name, "");
  const std::pair<const char*, const char*> boards[] = {{"ttyACM0", "A1"}, {"ttyACM1", "B2"}};
  int port = 1;
  for (const auto& [tty, serial] : boards) {
    const std::string usb = "1-" + std::to_string(port++);
    const fs::path device = root / "sys/devices/usb1" / usb;
    write_file(device / "idVendor", "2341");
    write_file(device / "idProduct", "0043");
    write_file(device / "serial", serial);
    fs::create_directories(device / (usb + ":1.0"));
    fs::create_directories(root / "sys/class/tty" / tty);
    fs::create_symlink("../../../devices/usb1/" + usb + "/" + usb + ":1.0", root / "sys/class/tty" / tty / "device");
    fs::create_symlink(std::string("../../") + tty, root / "dev/serial/by-id" / (std::string("usb-Arduino_Uno_") + serial + "-if00"));
  }
  const fs::path ch340 = root / "sys/devices/usb1/1-3";
  write_file(ch340 / "idVendor", "1a86");
  fs::create_directories(ch340 / "1-3:1.0/ttyUSB0");
  fs::create_directories(root / "sys/class/tty/ttyUSB0");
  fs::create_symlink("../../../devices/usb1/1-3/1-3:1.0/ttyUSB0", root / "sys/class/tty/ttyUSB0/device");
  return root;
}

PlanarProfile pantograph_with_serials(const std::string& first, const std::string& second) {
  PlanarProfile profile = load_planar_profile("hapkit_pantograph", ".");
  profile.board_serials = {first, second};
  return profile;
}

}  // namespace

TEST_CASE("board identity: the boards the profile names pass, by node or by-id link, from the real root's form") {
  const fs::path root = make_root();
  const PlanarProfile profile = pantograph_with_serials("A1", "B2");
  // As a user gives them (/dev/...), read under the stand-in root.
  CHECK_NOTHROW(check_board_identities(profile, {"/dev/ttyACM0", "/dev/ttyACM1"}, root.string()));
  CHECK_NOTHROW(check_board_identities(profile, {"/dev/serial/by-id/usb-Arduino_Uno_A1-if00", "/dev/ttyACM1"},
                                       root.string()));
  // A profile without board_serials checks nothing.
  CHECK_NOTHROW(check_board_identities(load_planar_profile("hapkit_pantograph", "."), {"/dev/ttyACM1", "/dev/ttyACM0"},
                                       root.string()));
  fs::remove_all(root);
}

TEST_CASE("board identity: swapped cables, a wrong board and a board without a serial number are refused") {
  const fs::path root = make_root();
  const PlanarProfile profile = pantograph_with_serials("A1", "B2");
  CHECK_THROWS_WITH_AS(check_board_identities(profile, {"/dev/ttyACM1", "/dev/ttyACM0"}, root.string()),
                       "--device serial:/dev/ttyACM1,/dev/ttyACM0: the cables are swapped: /dev/ttyACM1 is joint 2's "
                       "board (USB serial B2) and /dev/ttyACM0 joint 1's (A1), as profile \"hapkit_pantograph\" names "
                       "them; give serial:/dev/ttyACM0,/dev/ttyACM1 (in hapkit_pantograph (built-in profile): "
                       "/board_serials)",
                       InputError);
  CHECK_THROWS_WITH_AS(check_board_identities(pantograph_with_serials("A1", "C3"), {"/dev/ttyACM0", "/dev/ttyACM1"},
                                              root.string()),
                       doctest::Contains("(joint 2): /dev/ttyACM1 is the board with USB serial B2, not joint 2's (\"C3\")"),
                       InputError);
  CHECK_THROWS_WITH_AS(check_board_identities(profile, {"/dev/ttyACM0", "/dev/ttyUSB0"}, root.string()),
                       doctest::Contains("(joint 2): /dev/ttyUSB0: no USB serial number to check"), InputError);
  fs::remove_all(root);
}

TEST_CASE("board identity: board_serials in a profile file must be two different non-empty strings") {
  const fs::path dir = fs::temp_directory_path() / ("hapscene_board_serials_" + std::to_string(getpid()));
  fs::create_directories(dir);
  write_file(dir / "mine.json", R"({"extends": "hapkit_pantograph", "name": "mine", "board_serials": ["A1", "B2"]})");
  CHECK(load_planar_profile((dir / "mine.json").string(), ".").board_serials == std::array<std::string, 2>{"A1", "B2"});
  for (const char* bad : {R"(["A1"])", R"(["A1", ""])", R"(["A1", "A1"])", R"("A1,B2")"}) {
    write_file(dir / "bad.json",
               std::string(R"({"extends": "hapkit_pantograph", "name": "bad", "board_serials": )") + bad + "}");
    CHECK_THROWS_WITH_AS(load_planar_profile((dir / "bad.json").string(), "."), doctest::Contains("/board_serials"),
                         InputError);
  }
  // Checked against the boards (after parsing): the message names the file and the key.
  const fs::path root = make_root();
  const std::string mine = (dir / "mine.json").string();
  CHECK_THROWS_WITH_AS(check_board_identities(load_planar_profile(mine, "."), {"/dev/ttyACM0", "/dev/ttyUSB0"},
                                              root.string()),
                       doctest::Contains((mine + " (extends hapkit_pantograph): /board_serials").c_str()), InputError);
  fs::remove_all(root);
  fs::remove_all(dir);
}
