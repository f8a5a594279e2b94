#include "engine/devices/installed_files.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <vector>

namespace hapscene {
namespace {

bool is_executable_file(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error) && access(path.c_str(), X_OK) == 0;
}

bool is_file(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

// `relative` under the executable's folder, normalised; empty when either is unknown.
std::filesystem::path beside_executable(const char* relative) {
  const std::string dir = executable_dir();
  if (dir.empty() || relative == nullptr || *relative == '\0') return {};
  return (std::filesystem::path(dir) / relative).lexically_normal();
}

// The shared object holding this code (the Python module), or "" when it is the executable
// (dladdr names a file other than a .so).
std::string shared_object_file() {
  Dl_info info{};
  const bool found = dladdr(reinterpret_cast<void*>(&shared_object_file), &info) != 0 && info.dli_fname != nullptr;
  return found && std::string_view(info.dli_fname).find(".so") != std::string_view::npos ? info.dli_fname : "";
}

bool code_in_shared_object() { return !shared_object_file().empty(); }

// `from_bin` (a path from PREFIX/bin) from the Python module's folder instead, which is
// installed two levels deeper (PREFIX/lib/python3.X/dist-packages or
// PREFIX/lib/python3/dist-packages); empty for an executable.
std::filesystem::path beside_module(const char* from_bin) {
  if (!code_in_shared_object()) return {};
  return beside_executable(("../../" + std::string(from_bin)).c_str());
}

// This build's file, for an executable inside the build folder (or one whose folder is
// unknown); empty for an installed executable.
std::filesystem::path from_this_build(const char* build_path) {
  const std::string dir = executable_dir();
  if (!dir.empty()) {
    // /proc/self/exe has its symbolic links resolved: so must the build folder.
    std::error_code error;
    const std::filesystem::path build_dir = std::filesystem::weakly_canonical(install_layout().build_dir, error);
    const std::filesystem::path relative = std::filesystem::path(dir).lexically_relative(build_dir);
    if (relative.empty() || *relative.begin() == "..") return {};
  }
  return build_path;
}

// The places looked at, in order (empty ones left out).
std::vector<std::filesystem::path> board_places() {
  std::vector<std::filesystem::path> places;
  for (std::filesystem::path place : {beside_executable("hapscene-board"), beside_executable(install_layout().board_from_bin),
                                      beside_module(install_layout().board_from_bin),
                                      from_this_build(install_layout().board_build),
                                      std::filesystem::path(install_layout().board_installed)}) {
    if (!place.empty()) places.push_back(std::move(place));
  }
  return places;
}

std::vector<std::filesystem::path> firmware_places() {
  std::vector<std::filesystem::path> places;
  for (std::filesystem::path place :
       {beside_executable(install_layout().firmware_from_bin), beside_module(install_layout().firmware_from_bin),
        from_this_build(install_layout().firmware_build),
        std::filesystem::path(install_layout().firmware_installed)}) {
    if (!place.empty()) places.push_back(std::move(place));
  }
  return places;
}

std::string listed(const std::vector<std::filesystem::path>& places) {
  std::string text;
  for (const std::filesystem::path& place : places) text += (text.empty() ? "" : ", ") + place.string();
  return text.empty() ? "nowhere (the executable's folder is unknown)" : text;
}

}  // namespace

std::string executable_dir() {
  std::error_code error;
  // Loaded as a shared object (the Python module): that file's folder.
  if (const std::string module = shared_object_file(); !module.empty()) {
    const auto self = std::filesystem::weakly_canonical(module, error);
    if (!error) return self.parent_path().string();
  }
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string() : self.parent_path().string();
}

std::string find_board_program() {
  if (const char* chosen = std::getenv("HAPSCENE_BOARD"); chosen != nullptr && *chosen != '\0') {
    return is_executable_file(chosen) ? std::string(chosen) : std::string();
  }
  for (const std::filesystem::path& place : board_places()) {
    if (is_executable_file(place)) return place.string();
  }
  return {};
}

std::string find_default_firmware() {
  for (const std::filesystem::path& place : firmware_places()) {
    if (is_file(place)) return place.string();
  }
  return {};
}

std::string board_places_text() { return listed(board_places()); }
std::string firmware_places_text() { return listed(firmware_places()); }

}  // namespace hapscene
