#pragma once
// A version of the environment as the live view's page sees it: loaded from its text as a
// reload loads the file, and described for GET /api/scene (its device, effects, slider
// parameters, shapes and, in 1-D, the force curve at rest), on a job's thread
// (engine/serve/live_document.cpp runs it).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/run/hot_swap.hpp"
#include "engine/serve/parameters.hpp"

namespace hapscene {

// Its parameters and GET /api/scene's body (without the run's state).
struct VersionDescription {
  std::vector<LiveParameter> parameters;
  nlohmann::json scene_json;
};

// Loads a version of the environment from text, as a reload loads the file.
template <int N>
std::unique_ptr<LoadedSceneOf<N>> load_version(const std::string& text, const std::string& path,
                                               const std::string& base_dir);

// The description of `text` compiled as `scene`; `stride`: the stream's.
template <int N>
VersionDescription describe_version(const SceneOf<N>& scene, const std::string& text, const std::string& path,
                                    std::uint64_t stride);

// A version loaded and described.
template <int N>
struct PreparedVersion {
  std::unique_ptr<LoadedSceneOf<N>> loaded;
  VersionDescription description;
};

// An axis value as JSON: a number for N = 1, [x, y] for N = 2.
nlohmann::json axes_json(double value);
nlohmann::json axes_json(const Vec2& value);

}  // namespace hapscene
