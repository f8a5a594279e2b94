#pragma once
// The CPU-time budget for creating fresh script instances in an open-loop evaluation
// (1-D: OpenLoop; 2-D: PlanarOpenLoop). Each creation re-runs a script's top-level code;
// a script whose top level takes a large fraction of a second would make a scan of
// thousands of points take hours. The budget times each creation and refuses, before the
// work starts, an evaluation that would need more than kOpenLoopCreateBudget_s in all,
// with an InputError (exit 2) naming the scripts, their creation time and the number of
// points.
#include <cstddef>
#include <string>
#include <variant>

#include "engine/scene/scene.hpp"

namespace hapscene {

// CPU time an open loop may spend creating fresh script instances.
inline constexpr double kOpenLoopCreateBudget_s = 20.0;

// The script effects of a scene by name ("scripts/a.lua, scripts/b.lua"), for messages.
template <int N>
std::string script_names(const SceneOf<N>& scene) {
  std::string names;
  for (const auto& effect : scene.effects) {
    if (const auto* script = std::get_if<ScriptEffect>(&effect)) {
      names += (names.empty() ? "" : ", ") + script->program->display_name;
    }
  }
  return names;
}

class ScriptCreationBudget {
 public:
  // `who`: the environment file and its scripts ("env.json: scripts/a.lua"), or the
  // script alone when the environment is the script.
  explicit ScriptCreationBudget(std::string who) : who_(std::move(who)) {}
  template <int N>
  explicit ScriptCreationBudget(const SceneOf<N>& scene) : ScriptCreationBudget(owner(scene)) {}

  // The size of the evaluation under way, for the message.
  void set_points(std::size_t points) { points_ = points; }
  // Throws InputError when `count` more creations would exceed the budget (no-op until
  // the first creation has been timed).
  void require(std::size_t count) const;
  // Charges one creation that took `used_s` of CPU time.
  void charge(double used_s);

 private:
  template <int N>
  static std::string owner(const SceneOf<N>& scene) {
    const std::string scripts = script_names(scene);
    return scripts == scene.source_path ? scripts : scene.source_path + ": " + scripts;
  }

  std::string who_;
  double create_cpu_s_{-1.0};  // CPU time of the cheapest creation so far (-1: none yet)
  double spent_cpu_s_{};       // CPU time of all creations so far
  std::size_t created_{};
  std::size_t points_{};
};

}  // namespace hapscene
