#pragma once
// Files hapscene needs at run time besides its own program, for `--device hil`: the board
// simulator (hapscene-board) and the Hapkit firmware. An installed hapscene finds them
// where `cmake --install` put them, relative to its own executable (so a tree installed
// under any prefix, or moved whole, still works); a hapscene in its build tree, and the
// tests, find them where the build made them. An executable outside its build folder (an
// installed one) never looks in the build folder, so an install works or fails on its own.
// The layout comes from CMake (generated install_layout.cpp).
#include <string>

namespace hapscene {

struct InstallLayout {
  const char* board_from_bin;     // "../libexec/hapscene/hapscene-board"
  const char* firmware_from_bin;  // "../share/hapscene/firmware/hapkit_firmware.elf"
  const char* board_build;        // where this build made them (empty when it did not)
  const char* firmware_build;
  const char* build_dir;          // the build folder (CMAKE_BINARY_DIR)
  const char* board_installed;    // absolute, under the configured install prefix
  const char* firmware_installed;
};
const InstallLayout& install_layout();

// The folder of the file holding this code: the running executable's (from
// /proc/self/exe), or a shared object's when the engine is loaded as one (the Python
// module); empty when unknown.
std::string executable_dir();

// The board simulator: $HAPSCENE_BOARD when set, else hapscene-board next to the
// executable (a build tree), else the installed one (from the Python module: the one in
// the prefix it is installed under, two folders deeper than bin/), else (for an executable inside the
// build folder, such as the tests) this build's, else the one under the configured install
// prefix. Empty when none is an executable file.
std::string find_board_program();

// The firmware `--device hil` loads when no ELF is named: the installed one next to the
// executable's tree, else (inside the build folder) this build's, else the one under the
// configured install prefix. Empty when none is a file.
std::string find_default_firmware();

// Where the two searches above look, in order, for messages: "/usr/bin/hapscene-board,
// /usr/libexec/hapscene/hapscene-board".
std::string board_places_text();
std::string firmware_places_text();

}  // namespace hapscene
