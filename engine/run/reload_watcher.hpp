#pragma once
// Hot reload, the reload thread's side: watches an environment file and the script files
// it uses; when one changes, loads and compiles the new version off the loop, makes its
// script instances and offers it to the loop (engine/run/hot_swap.hpp). A broken new
// version is reported and the running one keeps going. Scenes the loop lets go of are
// destroyed here.
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "engine/run/hot_swap.hpp"

namespace hapscene {

class ReloadWatcher {
 public:
  using Report = std::function<void(const std::string& message)>;

  // Starts watching. `running` is the scene the run starts with; `report` is called from
  // the watcher's thread with one line per reload or failed reload. With a poll period of
  // 0 no thread is started and the owner calls poll() itself.
  ReloadWatcher(std::string environment_path, const Scene& running, SceneExchange* exchange,
                Report report, double poll_period_s = 0.2);
  // Stops the thread.
  ~ReloadWatcher();
  ReloadWatcher(const ReloadWatcher&) = delete;
  ReloadWatcher& operator=(const ReloadWatcher&) = delete;

  // Checks once (the thread calls this every poll period; without a thread, the owner).
  void poll();

 private:
  struct Stamp {
    std::filesystem::file_time_type time{};
    std::uintmax_t size{};
    bool operator==(const Stamp&) const = default;
  };

  void watch_files_of(const Scene& scene);
  std::vector<Stamp> stamps() const;
  void try_reload();

  std::string environment_path_;
  double rate_hz_;
  std::string device_name_;
  SceneExchange* exchange_;
  Report report_;
  std::vector<std::string> files_;
  std::vector<Stamp> stamps_;
  std::unique_ptr<LoadedScene> waiting_;  // compiled, not yet taken by the loop
  std::atomic<bool> stop_{false};
  double poll_period_s_;
  std::thread thread_;
};

}  // namespace hapscene
