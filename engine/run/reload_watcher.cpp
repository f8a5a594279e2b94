#include "engine/run/reload_watcher.hpp"

#include <chrono>
#include <system_error>

#include "engine/core/errors.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

ReloadWatcher::ReloadWatcher(std::string environment_path, const Scene& running,
                             SceneExchange* exchange, Report report, double poll_period_s)
    : environment_path_(std::move(environment_path)),
      rate_hz_(running.rate_hz),
      device_name_(running.device.name),
      exchange_(exchange),
      report_(std::move(report)),
      poll_period_s_(poll_period_s) {
  watch_files_of(running);
  if (poll_period_s_ <= 0.0) return;
  thread_ = std::thread([this] {
    while (!stop_.load()) {
      std::this_thread::sleep_for(std::chrono::duration<double>(poll_period_s_));
      poll();
    }
  });
}

ReloadWatcher::~ReloadWatcher() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

// The environment file and every script file it uses.
void ReloadWatcher::watch_files_of(const Scene& scene) {
  files_ = {environment_path_};
  for (const Effect& effect : scene.effects) {
    if (const auto* script = std::get_if<ScriptEffect>(&effect); script != nullptr && !script->file.empty()) {
      files_.push_back(script->file);
    }
  }
  stamps_ = stamps();
}

// Modification time and size of each watched file (zero for one that is missing).
std::vector<ReloadWatcher::Stamp> ReloadWatcher::stamps() const {
  std::vector<Stamp> out;
  for (const std::string& file : files_) {
    std::error_code error;
    Stamp stamp;
    stamp.time = std::filesystem::last_write_time(file, error);
    if (!error) stamp.size = std::filesystem::file_size(file, error);
    out.push_back(error ? Stamp{} : stamp);
  }
  return out;
}

void ReloadWatcher::poll() {
  // Destroy what the loop let go of.
  exchange_->take_retired().reset();
  // Offer what is compiled and waiting.
  if (waiting_ != nullptr && exchange_->offer(waiting_)) {
    report_("reloaded " + environment_path_ + ": cross-fading to the new version");
  }
  // Look for changes.
  const std::vector<Stamp> now = stamps();
  if (now == stamps_) return;
  stamps_ = now;
  try_reload();
}

void ReloadWatcher::try_reload() {
  try {
    auto next = std::make_unique<LoadedScene>();
    next->scene = load_environment_file(environment_path_);
    if (next->scene.rate_hz != rate_hz_ || next->scene.device.name != device_name_) {
      throw InputError(environment_path_ + ": rate_hz and device cannot change during a run");
    }
    next->scripts = make_script_instances(next->scene);
    watch_files_of(next->scene);
    waiting_ = std::move(next);
    if (exchange_->offer(waiting_)) {
      report_("reloaded " + environment_path_ + ": cross-fading to the new version");
    }
  } catch (const std::exception& error) {
    report_(std::string("reload failed, keeping the running version: ") + error.what());
  }
}

}  // namespace hapscene
