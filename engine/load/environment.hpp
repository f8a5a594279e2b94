#pragma once
// Loading an environment file into a compiled Scene: parse, check every value with a
// located error, then compile (device profile, safety limits, what the effects need).
// The file's harness settings (its "validate" block) are checked at every load too, and
// come back beside the scene (Environment) for the commands that run the harness.
#include <string>
#include <string_view>

#include "engine/load/validate_thresholds.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// An environment file as loaded: the scene the tick runs, and what the harness judges it
// by (the "validate" block over the defaults), for a device of N axes.
template <int N>
struct EnvironmentOf {
  static constexpr int kAxes = N;
  SceneOf<N> scene;
  ValidateThresholds validate;
};
using Environment = EnvironmentOf<1>;
using PlanarEnvironment = EnvironmentOf<2>;

// An environment of whatever N its device has: one of EnvironmentOf<N> for each N of
// HAPSCENE_FOR_EACH_AXES. Commands that take any environment load this (the file is read
// and parsed once) and visit it with code written once over N.
using AnyEnvironment = AxesVariant<EnvironmentOf>;

// Loads an environment file (JSON, or a .lua script as its one-effect environment) for
// the N its "device" names. Throws InputError naming the file and the place. Its load
// warnings (SceneOf<N>::load_warnings) are also printed to stderr.
AnyEnvironment load_any_environment(const std::string& path);
// Compiles environment JSON text; `display_name` names it in messages and relative paths
// in it (a device profile, scripts) are taken from `base_dir`. Load warnings stay in the
// scene, unprinted.
AnyEnvironment compile_any_environment(std::string_view json_text, const std::string& display_name,
                                       const std::string& base_dir = ".");
// The N of a loaded environment.
int axes_of(const AnyEnvironment& environment);

// The same for a command that takes environments of one N only: a file whose device has
// another N is refused with a located error.
template <int N>
EnvironmentOf<N> load_environment_of(const std::string& path);
template <int N>
EnvironmentOf<N> compile_environment_of(std::string_view json_text, const std::string& display_name,
                                        const std::string& base_dir = ".");

// The 1-DOF names, as most 1-DOF code reads them.
inline Environment load_environment(const std::string& path) { return load_environment_of<1>(path); }
inline Environment compile_environment(std::string_view json_text, const std::string& display_name,
                                       const std::string& base_dir = ".") {
  return compile_environment_of<1>(json_text, display_name, base_dir);
}
inline Scene load_environment_file(const std::string& path) { return load_environment_of<1>(path).scene; }
inline Scene load_environment_text(std::string_view json_text, const std::string& display_name,
                                   const std::string& base_dir = ".") {
  return compile_environment_of<1>(json_text, display_name, base_dir).scene;
}

// The environment JSON text a file stands for: a JSON file's own text, or for a script
// (.lua) the one-effect environment that runs it with its default parameters (named after
// the file), as load_environment loads it. Throws InputError when it cannot be read.
std::string environment_text_of(const std::string& path);

// The number of axes of the scene an environment file makes: 2 when its "device" is a
// planar profile, else 1. Throws InputError when the file cannot be read or parsed.
int environment_axes(const std::string& path);
// The same for environment JSON text (relative profile paths from `base_dir`).
int environment_text_axes(std::string_view json_text, const std::string& display_name,
                          const std::string& base_dir = ".");

// The 2-DOF names (docs/reference/environments.md, "2-D environments").
inline PlanarEnvironment load_planar_environment(const std::string& path) { return load_environment_of<2>(path); }
inline PlanarEnvironment compile_planar_environment(std::string_view json_text, const std::string& display_name,
                                                    const std::string& base_dir = ".") {
  return compile_environment_of<2>(json_text, display_name, base_dir);
}
inline PlanarScene load_planar_environment_file(const std::string& path) { return load_environment_of<2>(path).scene; }
inline PlanarScene load_planar_environment_text(std::string_view json_text, const std::string& display_name,
                                                const std::string& base_dir = ".") {
  return compile_environment_of<2>(json_text, display_name, base_dir).scene;
}

}  // namespace hapscene
