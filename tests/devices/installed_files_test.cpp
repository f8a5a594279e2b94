// Where hapscene finds the board simulator and the firmware for `--device hil`
// (engine/devices/installed_files.hpp): relative to its executable for an installed tree
// (tested end to end by the ctest install_tree), this build's files for a program inside
// the build folder such as this test, and $HAPSCENE_BOARD when set.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>

#include "engine/devices/installed_files.hpp"

using namespace hapscene;

namespace {

// Sets an environment variable for one scope.
struct ScopedVariable {
  std::string name;
  ScopedVariable(std::string variable, const char* value) : name(std::move(variable)) {
    ::setenv(name.c_str(), value, 1);
  }
  ~ScopedVariable() { ::unsetenv(name.c_str()); }
};

}  // namespace

TEST_CASE("installed files: the layout is relative to the executable's folder") {
  const InstallLayout& layout = install_layout();
  CHECK(std::filesystem::path(layout.board_from_bin).is_relative());
  CHECK(std::filesystem::path(layout.firmware_from_bin).is_relative());
  CHECK(std::string(layout.board_from_bin).ends_with("hapscene/hapscene-board"));
  CHECK(std::string(layout.firmware_from_bin).ends_with("hapscene/firmware/hapkit_firmware.elf"));
  CHECK(!executable_dir().empty());
}

#if HAPSCENE_HAVE_HIL
TEST_CASE("installed files: a program inside the build folder finds this build's board and firmware") {
  CHECK(find_default_firmware() == install_layout().firmware_build);
  CHECK(find_board_program() == install_layout().board_build);
  CHECK(board_places_text().find(install_layout().board_build) != std::string::npos);
  CHECK(firmware_places_text().find(install_layout().firmware_build) != std::string::npos);
}
#endif

TEST_CASE("installed files: $HAPSCENE_BOARD names the board simulator") {
  {
    const ScopedVariable board("HAPSCENE_BOARD", "/bin/true");
    CHECK(find_board_program() == "/bin/true");
  }
  {
    // Not an executable file: nothing is found, rather than another board.
    const ScopedVariable board("HAPSCENE_BOARD", "/nonexistent/hapscene-board");
    CHECK(find_board_program().empty());
  }
  {
    const ScopedVariable board("HAPSCENE_BOARD", HAPSCENE_SOURCE_DIR "/README.md");
    CHECK(find_board_program().empty());
  }
}
