#pragma once
// A folder of files for one test, under the system's temporary directory, made empty at
// the start and removed at the end. Its name carries a tag and the process id, so tests
// running in parallel never share one.
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <doctest/doctest.h>

namespace hapscene::test {

struct ScratchFolder {
  std::filesystem::path dir;

  explicit ScratchFolder(const std::string& tag)
      : dir(std::filesystem::temp_directory_path() / ("hapscene_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~ScratchFolder() { std::filesystem::remove_all(dir); }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  // Writes (or rewrites) `name`. A rewrite moves the file's time forward by a second:
  // file times can be coarser than a test's edits, and a reload watcher must see each.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto path = dir / name;
    std::filesystem::create_directories(path.parent_path());
    const bool existed = std::filesystem::exists(path);
    const auto before = existed ? std::filesystem::last_write_time(path) : std::filesystem::file_time_type{};
    std::ofstream(path) << text;
    if (existed) std::filesystem::last_write_time(path, before + std::chrono::seconds(1));
    return path;
  }

  // Makes a named pipe `name`.
  std::string fifo(const std::string& name) const {
    const std::string path = (dir / name).string();
    REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
    return path;
  }
};

}  // namespace hapscene::test
