#include "engine/serve/live_document.hpp"

#include <httplib.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "engine/base/errors.hpp"
#include "engine/base/file_replace.hpp"
#include "engine/load/environment.hpp"
#include "engine/serve/live_job.hpp"
#include "engine/serve/live_requests.hpp"

namespace hapscene {

using json = nlohmann::json;

namespace {

std::filesystem::file_time_type stamp_of(const std::string& path) {
  std::error_code error;
  const auto stamp = std::filesystem::last_write_time(path, error);
  return error ? std::filesystem::file_time_type{} : stamp;
}

}  // namespace

template <int N>
LiveDocumentOf<N>::LiveDocumentOf(std::string path, const SceneOf<N>& scene, std::uint64_t stride,
                                  const std::atomic<bool>& stopping)
    : path_(std::move(path)), stride_(stride), stopping_(stopping) {
  base_dir_ = std::filesystem::path(path_).parent_path().string();
  if (base_dir_.empty()) base_dir_ = ".";
  text_ = environment_text_of(path_);
  file_text_ = text_;
  file_stamp_ = stamp_of(path_);
  take(describe_version<N>(scene, text_, path_, stride_));
}

template <int N>
void LiveDocumentOf<N>::take(VersionDescription description) {
  parameters_ = std::move(description.parameters);
  scene_json_ = std::move(description.scene_json);
}

template <int N>
std::optional<PreparedVersion<N>> LiveDocumentOf<N>::prepare(const std::string& candidate) {
  return run_job<PreparedVersion<N>>(
      [candidate, file = path_, dir = base_dir_, stride = stride_] {
        PreparedVersion<N> out;
        out.loaded = load_version<N>(candidate, file, dir);
        out.description = describe_version<N>(out.loaded->scene, candidate, file, stride);
        return out;
      },
      stopping_);
}

// The file changed on disk since it was last read or written (an editor saved it; the
// watcher reloads it), or the watcher took a new version from the files (a script's
// defaults edited): the file's text becomes the current values, described as the loop
// now runs them.
template <int N>
void LiveDocumentOf<N>::refresh_from_file() {
  const auto stamp = stamp_of(path_);
  const std::uint64_t versions = watcher_ != nullptr ? watcher_->file_versions() : 0;
  if (stamp == file_stamp_ && versions == seen_file_versions_) return;
  file_stamp_ = stamp;
  seen_file_versions_ = versions;
  try {
    const std::string fresh = environment_text_of(path_);
    std::optional<PreparedVersion<N>> prepared = prepare(fresh);
    if (!prepared) return;
    take(std::move(prepared->description));
    text_ = fresh;
    file_text_ = fresh;
  } catch (const std::exception&) {
    // A broken file: the running version (and these values) keep going, as a reload does.
  }
}

template <int N>
json LiveDocumentOf<N>::described() const {
  json out = scene_json_;
  out["unsaved"] = text_ != file_text_;
  return out;
}

template <int N>
json LiveDocumentOf<N>::scene(const AddRunState& add_state) {
  std::lock_guard lock(mutex_);
  refresh_from_file();
  return add_state(described());
}

template <int N>
void LiveDocumentOf<N>::change(const std::string& request_body, httplib::Response& res, const AddRunState& add_state) {
  json body;
  try {
    body = json::parse(request_body);
  } catch (const json::exception&) {
    error_response(res, 400, "request: expected a JSON object {\"effect\": I, \"parameter\": NAME, \"value\": V}");
    return;
  }
  if (!body.is_object() || !body.contains("effect") || !body["effect"].is_number_unsigned() ||
      !body.contains("parameter") || !body["parameter"].is_string() || !body.contains("value")) {
    error_response(res, 400, "request: expected a JSON object {\"effect\": I, \"parameter\": NAME, \"value\": V}");
    return;
  }
  std::lock_guard lock(mutex_);
  refresh_from_file();
  try {
    const std::string candidate = with_parameter(text_, parameters_, body["effect"].get<std::size_t>(),
                                                 body["parameter"].get<std::string>(), body["value"]);
    std::optional<PreparedVersion<N>> prepared = prepare(candidate);
    if (!prepared) {
      error_response(res, 503, "the run is ending");
      return;
    }
    // Described before it is handed over (the loop owns it from then on).
    const std::string refusal = watcher_->offer_version(std::move(prepared->loaded));
    if (!refusal.empty()) {
      error_response(res, 400, refusal);
      return;
    }
    take(std::move(prepared->description));
    text_ = candidate;
    res.set_content(add_state(described()).dump(), "application/json");
  } catch (const std::exception& error) {
    error_response(res, 400, error.what());
  }
}

// Replaces the file whole (engine/base/file_replace.hpp: never through a link planted
// next to it), through the watcher so that it does not reload what it wrote.
template <int N>
void LiveDocumentOf<N>::save(httplib::Response& res) {
  std::lock_guard lock(mutex_);
  refresh_from_file();
  if (std::filesystem::path(path_).extension() == ".lua") {
    error_response(res, 409,
                   path_ + ": a script run as an environment of its own has no environment file to save values "
                           "into (its changed values last for this run); to keep them, run an environment file "
                           "that names the script and gives them as \"params\" (hapscene new script NAME)");
    return;
  }
  const std::string problem = watcher_->write_watched([&]() -> std::string {
    const FileWriteOutcome outcome = replace_file(path_, text_, SpecialPath::refuse);
    if (outcome.ok()) return {};
    const std::string reason = std::strerror(outcome.error_number);
    if (outcome.failed == FileWriteStep::open) return path_ + ": cannot write a new file next to it (" + reason + ")";
    return path_ + ": cannot replace the file (" + reason + ")";
  });
  if (!problem.empty()) {
    error_response(res, 500, problem);
    return;
  }
  file_text_ = text_;
  file_stamp_ = stamp_of(path_);
  res.set_content(json{{"saved", path_}, {"bytes", text_.size()}}.dump(), "application/json");
}

template <int N>
std::string LiveDocumentOf<N>::current_text() {
  std::lock_guard lock(mutex_);
  refresh_from_file();  // the version the loop runs, after any reload
  return text_;
}

template <int N>
std::pair<Axes<N>, Axes<N>> LiveDocumentOf<N>::workspace_m() {
  std::lock_guard lock(mutex_);
  const json& device = scene_json_["device"];
  std::pair<Axes<N>, Axes<N>> out{};
  for (int i = 0; i < N; ++i) {
    const json& low = N == 1 ? device["workspace_min_m"] : device["workspace_min_m"][static_cast<std::size_t>(i)];
    const json& high = N == 1 ? device["workspace_max_m"] : device["workspace_max_m"][static_cast<std::size_t>(i)];
    set_component(out.first, i, low.get<double>());
    set_component(out.second, i, high.get<double>());
  }
  return out;
}

#define HAPSCENE_LIVE_DOCUMENT(N) template class LiveDocumentOf<N>;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_LIVE_DOCUMENT)
#undef HAPSCENE_LIVE_DOCUMENT

}  // namespace hapscene
