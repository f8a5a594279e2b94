#pragma once
// The live view's document: the environment's text with the page's changes (what save
// writes), the file as last read or written, and the running version's description
// (its slider parameters and GET /api/scene's body). POST /api/params loads a changed
// version and hands it to the run's watcher (a hot reload's checks and cross-fade); POST
// /api/save replaces the file; a change on disk (an editor's save, a reload by the
// watcher) becomes the document again before any request reads it.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/run/reload_watcher.hpp"
#include "engine/scene/scene.hpp"
#include "engine/serve/parameters.hpp"
#include "engine/serve/version_description.hpp"

namespace httplib {
struct Response;
}

namespace hapscene {

template <int N>
class LiveDocumentOf {
 public:
  // The scene's body with the run's state the view adds (the device's links, the hand,
  // the script faults). Called with the document's lock held.
  using AddRunState = std::function<nlohmann::json(nlohmann::json scene)>;

  // Reads the file; `scene` is the version the run starts with, `stride` the stream's.
  // `stopping` is the view's: set, a load in progress is abandoned.
  LiveDocumentOf(std::string path, const SceneOf<N>& scene, std::uint64_t stride, const std::atomic<bool>& stopping);
  LiveDocumentOf(const LiveDocumentOf&) = delete;
  LiveDocumentOf& operator=(const LiveDocumentOf&) = delete;

  // Where changes go (before serving).
  void set_watcher(ReloadWatcherOf<N>* watcher) noexcept { watcher_ = watcher; }

  // GET /api/scene.
  nlohmann::json scene(const AddRunState& add_state);
  // POST /api/params: {"effect": I, "parameter": NAME, "value": V}; 200 with the scene, 400
  // refused (the loader's or the watcher's words), 503 when the run is ending.
  void change(const std::string& request_body, httplib::Response& res, const AddRunState& add_state);
  // POST /api/save: the current values into the file, replacing it whole.
  void save(httplib::Response& res);

  // The current values (after any change on disk): the version validate runs.
  std::string current_text();
  // The running version's workspace, as GET /api/scene gives it to the page.
  std::pair<Axes<N>, Axes<N>> workspace_m();

  const std::string& path() const noexcept { return path_; }
  const std::string& base_dir() const noexcept { return base_dir_; }

 private:
  void take(VersionDescription description);
  // Loads and describes `candidate` on a job's thread (nullopt: the view stopped first).
  // Throws what the loader throws.
  std::optional<PreparedVersion<N>> prepare(const std::string& candidate);
  // With mutex_ held; every request calls it first.
  void refresh_from_file();
  // The running version's scene body, with whether the values differ from the file's
  // (mutex_ held).
  nlohmann::json described() const;

  std::string path_;
  std::string base_dir_;
  std::uint64_t stride_{};
  const std::atomic<bool>& stopping_;
  ReloadWatcherOf<N>* watcher_{};

  std::mutex mutex_;       // everything below
  std::string text_;       // the current values: what save writes
  std::string file_text_;  // the file as last read or written
  std::filesystem::file_time_type file_stamp_{};
  std::uint64_t seen_file_versions_{};  // the watcher's file_versions() when last read
  std::vector<LiveParameter> parameters_;
  nlohmann::json scene_json_;
};

}  // namespace hapscene
