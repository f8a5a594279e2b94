#include "engine/run/reload_watcher.hpp"

#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <variant>

#include "engine/base/object_reader.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/reload_guard.hpp"

namespace hapscene {

namespace {

std::atomic<std::uint64_t> g_abandoned_loads{0};

// After this many loads were abandoned, watching stops (each may still hold a thread).
constexpr int kMaxAbandonedLoads = 2;

// A new version the run cannot take whatever it holds: not a load failure.
struct RefusedLoad : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The default load: the environment file, loaded once for the N its device names, with its
// script instances. A file that now makes a scene of another axis count names another
// device: refused.
template <int N>
std::unique_ptr<LoadedSceneOf<N>> load_scene(const std::string& path) {
  AnyEnvironment environment = load_any_environment(path);
  if (auto* same = std::get_if<EnvironmentOf<N>>(&environment)) return make_loaded_scene<N>(std::move(same->scene));
  const char* now = std::visit([](const auto& e) { return SceneParts<std::decay_t<decltype(e)>::kAxes>::kKindName; },
                               environment);
  throw RefusedLoad(std::string("the device cannot change during a run (the file now makes a ") + now +
                    " scene; this run's is " + SceneParts<N>::kKindName + ")");
}

}  // namespace

std::uint64_t abandoned_reload_loads() noexcept { return g_abandoned_loads.load(); }

template <int N>
ReloadWatcherOf<N>::ReloadWatcherOf(std::string environment_path, const Scene& running,
                                    SceneExchangeOf<N>* exchange, Report report, ReloadWatcherOptionsOf<N> options)
    : environment_path_(std::move(environment_path)),
      exchange_(exchange),
      report_(std::move(report)),
      options_(std::move(options)) {
  if (!options_.load) options_.load = load_scene<N>;
  limits_.rate_hz = running.rate_hz;
  limits_.device = running.device;
  limits_.safety = running.safety;
  watch_files_of(running, {});
  if (options_.poll_period_s <= 0.0) return;
  // Waits one poll period between polls, or until the destructor says stop: the run ends
  // when its last tick does, not up to a poll period later.
  thread_ = std::thread([this] {
    const auto period = std::chrono::duration<double>(options_.poll_period_s);
    std::unique_lock lock(stop_mutex_);
    while (!stop_wake_.wait_for(lock, period, [this] { return stop_.load(); })) {
      lock.unlock();
      poll();
      lock.lock();
    }
  });
}

template <int N>
ReloadWatcherOf<N>::~ReloadWatcherOf() {
  {
    std::lock_guard lock(stop_mutex_);
    stop_.store(true);
  }
  stop_wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (job_ != nullptr) {
    bool done = false;
    {
      std::lock_guard lock(job_->mutex);
      done = job_->done;
    }
    if (done) {
      job_thread_.join();
    } else {
      abandon_load("the run ended while it was still loading");
    }
  }
}

template <int N>
typename ReloadWatcherOf<N>::Stamp ReloadWatcherOf<N>::stamp_of(const std::string& path) {
  std::error_code error;
  Stamp stamp;
  stamp.time = std::filesystem::last_write_time(path, error);
  if (!error) stamp.size = std::filesystem::file_size(path, error);
  return error ? Stamp{} : stamp;
}

// The environment file and every script file it uses. A file that was watched when the
// load started keeps the stamp it had then, so an edit made during the load is seen.
template <int N>
void ReloadWatcherOf<N>::watch_files_of(const Scene& scene, const std::vector<Watched>& at_load_start) {
  std::vector<std::string> paths{environment_path_};
  for (const auto& effect : scene.effects) {
    if (const auto* script = std::get_if<ScriptEffect>(&effect); script != nullptr && !script->file.empty()) {
      paths.push_back(script->file);
    }
  }
  files_.clear();
  for (const std::string& path : paths) {
    Watched watched{path, stamp_of(path)};
    for (const Watched& before : at_load_start) {
      if (before.path == path) watched.stamp = before.stamp;
    }
    files_.push_back(std::move(watched));
  }
}

template <int N>
bool ReloadWatcherOf<N>::changed() const {
  for (const Watched& watched : files_) {
    if (!(stamp_of(watched.path) == watched.stamp)) return true;
  }
  return false;
}

template <int N>
void ReloadWatcherOf<N>::poll() {
  std::lock_guard guard(mutex_);
  // Destroy what the loop let go of; a fault of a replaced version is reported here
  // (the run's summary covers only the version running at the end).
  if (std::unique_ptr<LoadedScene> retired = exchange_->take_retired()) {
    if (options_.before_destroy) options_.before_destroy(*retired);
    for (const auto& script : retired->scripts) {
      if (script->disabled()) {
        report_("a replaced version's script had been disabled: " + std::string(script->fault_message()));
        replaced_script_faults_.fetch_add(1);
      }
    }
  }
  // A load in flight: take its result, or give up on it when overdue.
  if (job_ != nullptr) collect_load();
  // Offer what is compiled and waiting.
  if (waiting_ != nullptr && exchange_->offer(waiting_)) {
    report_("reloaded " + environment_path_ + ": cross-fading to the new version");
  }
  if (job_ != nullptr || stopped_watching_ || !options_.watch_files || !changed()) return;
  start_load();
  if (options_.poll_period_s > 0.0) return;
  // Without a thread: wait for the load here, at most the compile timeout.
  {
    std::unique_lock lock(job_->mutex);
    const std::shared_ptr<Job> job = job_;
    job->finished.wait_for(lock, std::chrono::duration<double>(options_.compile_timeout_s),
                           [&] { return job->done; });
  }
  collect_load();
}

template <int N>
void ReloadWatcherOf<N>::start_load() {
  for (Watched& watched : files_) watched.stamp = stamp_of(watched.path);
  load_start_files_ = files_;
  job_ = std::make_shared<Job>();
  job_started_ = std::chrono::steady_clock::now();
  // The thread holds its own references: it may outlive this watcher when abandoned.
  job_thread_ = std::thread([job = job_, load = options_.load, path = environment_path_] {
    std::unique_ptr<LoadedScene> scene;
    std::string error;
    bool refused = false;
    try {
      scene = load(path);
      if (scene == nullptr) error = path + ": the load gave no scene";
    } catch (const RefusedLoad& caught) {
      error = caught.what();
      refused = true;
    } catch (const std::exception& caught) {
      error = caught.what();
    } catch (...) {
      error = "unknown error";
    }
    std::lock_guard lock(job->mutex);
    job->scene = std::move(scene);
    job->error = std::move(error);
    job->refused = refused;
    job->done = true;
    job->finished.notify_all();
  });
}

template <int N>
void ReloadWatcherOf<N>::collect_load() {
  std::unique_ptr<LoadedScene> next;
  std::string error;
  bool done = false;
  bool refused = false;
  {
    std::lock_guard lock(job_->mutex);
    done = job_->done;
    if (done) {
      next = std::move(job_->scene);
      error = std::move(job_->error);
      refused = job_->refused;
    }
  }
  if (!done) {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - job_started_;
    if (elapsed.count() < options_.compile_timeout_s) return;
    abandon_load("it did not finish within " + format_number(options_.compile_timeout_s) + " s");
    return;
  }
  job_thread_.join();
  job_.reset();
  if (refused) {
    report_("reload refused, keeping the running version: " + environment_path_ + ": " + error);
    return;
  }
  if (next == nullptr) {
    report_("reload failed, keeping the running version: " + error);
    return;
  }
  accept(std::move(next));
}

// A load that does not end: its thread is left to finish on its own (it holds only its
// own data) and no later load waits for it.
template <int N>
void ReloadWatcherOf<N>::abandon_load(const std::string& why) {
  job_thread_.detach();
  job_.reset();
  g_abandoned_loads.fetch_add(1);
  ++abandoned_here_;
  std::string message = "reload of " + environment_path_ + " abandoned, keeping the running version: " + why;
  if (abandoned_here_ >= kMaxAbandonedLoads && !stop_.load()) {
    stopped_watching_ = true;
    message += "; hot reload is off for the rest of this run (" + std::to_string(abandoned_here_) +
               " loads did not finish)";
  }
  report_(message);
}

// A compiled version: refused when it would change the device or loosen a limit.
template <int N>
void ReloadWatcherOf<N>::accept(std::unique_ptr<LoadedScene> next) {
  const std::string refusal = reload_refusal(limits_, next->scene);
  if (!refusal.empty()) {
    report_("reload refused, keeping the running version: " + environment_path_ + ": " + refusal);
    return;
  }
  limits_.safety = next->scene.safety;
  watch_files_of(next->scene, load_start_files_);
  waiting_ = std::move(next);
  file_versions_.fetch_add(1);
  if (exchange_->offer(waiting_)) {
    report_("reloaded " + environment_path_ + ": cross-fading to the new version");
  }
}

template <int N>
std::string ReloadWatcherOf<N>::offer_version(std::unique_ptr<LoadedScene> next) {
  std::lock_guard guard(mutex_);
  if (next == nullptr) return "no version to offer";
  const std::string refusal = reload_refusal(limits_, next->scene);
  if (!refusal.empty()) {
    report_("change refused, keeping the running version: " + environment_path_ + ": " + refusal);
    return environment_path_ + ": " + refusal;
  }
  limits_.safety = next->scene.safety;
  // An older version still waiting for the slot was never offered: the newer one replaces it.
  waiting_ = std::move(next);
  if (exchange_->offer(waiting_)) {
    report_("changed " + environment_path_ + " from the live view: cross-fading to the new version");
  }
  return {};
}

template <int N>
std::string ReloadWatcherOf<N>::write_watched(const std::function<std::string()>& write) {
  std::lock_guard guard(mutex_);
  const std::string result = write();
  for (Watched& watched : files_) watched.stamp = stamp_of(watched.path);
  return result;
}

// The axis counts scenes are compiled for.
#define HAPSCENE_RELOAD_WATCHER(N) template class ReloadWatcherOf<N>;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_RELOAD_WATCHER)
#undef HAPSCENE_RELOAD_WATCHER

}  // namespace hapscene
