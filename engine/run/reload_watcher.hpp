#pragma once
// Hot reload, the reload thread's side: watches an environment file and the script files
// it uses; when one changes, loads and compiles the new version off the loop, makes its
// script instances and offers it to the loop (engine/run/hot_swap.hpp). A broken new
// version, or one that would change the device or loosen a safety limit
// (engine/run/reload_guard.hpp), or one that makes a scene of another number of axes, is
// reported and the running one keeps going. Scenes the loop lets go of are destroyed
// here. Written once for the 1-DOF and the planar scenes (ReloadWatcherOf<N>).
//
// Nothing here waits unboundedly on a load: each load runs on a thread of its own, and
// the watcher only looks at it when it polls. A load still running after the compile
// timeout is reported and abandoned (its thread detached; it ends when its own limits
// stop it), and so is one still running when the watcher is destroyed, so the run
// always ends.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/run/hot_swap.hpp"

namespace hapscene {

template <int N>
struct ReloadWatcherOptionsOf {
  // How often the files are looked at; 0: no thread, the owner calls poll() (which then
  // waits for the load it starts, at most compile_timeout_s).
  double poll_period_s{0.2};
  // A load taking longer is reported and abandoned.
  double compile_timeout_s{10.0};
  // Called on the watcher's thread with each scene the loop let go of, just before it is
  // destroyed (the live status drains its scripts' log messages here).
  std::function<void(LoadedSceneOf<N>& retired)> before_destroy;
  // Loads a new version (tests replace it); the default loads the environment file and
  // makes its script instances, and refuses a file that now makes a scene with another
  // number of axes (another device).
  std::function<std::unique_ptr<LoadedSceneOf<N>>(const std::string& path)> load;
  // False: the files are not watched (--no-reload with the live view, which still offers
  // versions through offer_version); retired scenes are still destroyed here.
  bool watch_files{true};
};

using ReloadWatcherOptions = ReloadWatcherOptionsOf<1>;

// Loads abandoned by every watcher of this process, whatever its scene's axes.
std::uint64_t abandoned_reload_loads() noexcept;

// Watches the files of a scene with N axes (1: the Hapkit's; 2: a planar device's).
template <int N>
class ReloadWatcherOf {
 public:
  using Report = std::function<void(const std::string& message)>;
  using LoadedScene = LoadedSceneOf<N>;
  using Scene = SceneOf<N>;

  // Starts watching. `running` is the scene the run starts with; `report` is called from
  // the watcher's thread with one line per reload or failed reload.
  ReloadWatcherOf(std::string environment_path, const Scene& running, SceneExchangeOf<N>* exchange,
                  Report report, ReloadWatcherOptionsOf<N> options = {});
  // Stops the thread at once (it is woken from its wait between polls); abandons a load
  // still running (never waits for it).
  ~ReloadWatcherOf();
  ReloadWatcherOf(const ReloadWatcherOf&) = delete;
  ReloadWatcherOf& operator=(const ReloadWatcherOf&) = delete;

  // Checks once (the thread calls this every poll period; without a thread, the owner).
  void poll();

  // Offers a version compiled elsewhere (the live view's parameter change, from its
  // text) through the same check as a reload of the file: "" when it is offered to the
  // loop (or waits for the slot, replacing an older version still waiting), else why it
  // is refused (the running version keeps going). Reported like a reload. Any thread.
  std::string offer_version(std::unique_ptr<LoadedScene> next);

  // Runs `write` (which writes the environment file) so that the watcher does not take
  // the file it writes for an edit: the watched stamps are taken again afterwards. Returns
  // what `write` returns. Any thread.
  std::string write_watched(const std::function<std::string()>& write);

  // Loads abandoned by every watcher of this process (their threads may still run: the
  // process should then end with std::_Exit after flushing its output).
  static std::uint64_t abandoned_loads() noexcept { return abandoned_reload_loads(); }

  // Versions compiled from the files and offered to the loop (reloads): whoever shows the
  // scene (the live view) reads it again when this changes, so that it never describes a
  // version the loop no longer runs. Any thread.
  std::uint64_t file_versions() const noexcept { return file_versions_.load(); }

  // Scripts of replaced versions that had been disabled by a fault (each was reported).
  std::uint64_t replaced_script_faults() const noexcept { return replaced_script_faults_.load(); }

 private:
  struct Stamp {
    std::filesystem::file_time_type time{};
    std::uintmax_t size{};
    bool operator==(const Stamp&) const = default;
  };
  struct Watched {
    std::string path;
    Stamp stamp;
  };
  // One load on its own thread; shared with that thread so it may outlive the watcher.
  struct Job {
    std::mutex mutex;
    std::condition_variable finished;
    bool done{false};
    std::unique_ptr<LoadedScene> scene;
    std::string error;
    bool refused{};  // the file makes a scene the run cannot take (error says why)
  };

  static Stamp stamp_of(const std::string& path);
  void watch_files_of(const Scene& scene, const std::vector<Watched>& at_load_start);
  bool changed() const;
  void start_load();
  void collect_load();
  void abandon_load(const std::string& why);
  void accept(std::unique_ptr<LoadedScene> next);

  std::string environment_path_;
  Scene limits_;  // rate, device and safety in force (the last version accepted)
  SceneExchangeOf<N>* exchange_;
  Report report_;
  ReloadWatcherOptionsOf<N> options_;
  std::vector<Watched> files_;
  std::vector<Watched> load_start_files_;  // the stamps the running load started from
  std::unique_ptr<LoadedScene> waiting_;   // compiled, not yet taken by the loop
  std::shared_ptr<Job> job_;               // the load in flight, if any
  std::thread job_thread_;
  std::atomic<std::uint64_t> replaced_script_faults_{0};
  std::atomic<std::uint64_t> file_versions_{0};
  std::chrono::steady_clock::time_point job_started_;
  int abandoned_here_{0};
  bool stopped_watching_{false};
  std::atomic<bool> stop_{false};
  std::mutex stop_mutex_;                // guards the stop signal for stop_wake_
  std::condition_variable stop_wake_;   // wakes the watcher's thread from its wait on stop
  std::mutex mutex_;  // poll, offer_version and write_watched, all off the loop
  std::thread thread_;
};

using ReloadWatcher = ReloadWatcherOf<1>;

}  // namespace hapscene
