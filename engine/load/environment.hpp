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
// by (the "validate" block over the defaults).
struct Environment {
  Scene scene;
  ValidateThresholds validate;
};

// Loads an environment file. Throws InputError naming the file and the place. Its load
// warnings (Scene::load_warnings) are also printed to stderr.
Environment load_environment(const std::string& path);

// Compiles environment JSON text; `display_name` names it in messages and relative
// paths in it (a device profile) are taken from `base_dir`. Throws InputError. Load
// warnings stay in the scene, unprinted.
Environment compile_environment(std::string_view json_text, const std::string& display_name,
                                const std::string& base_dir = ".");

// The same, for the commands that need only the scene (the validate block is still checked).
Scene load_environment_file(const std::string& path);
Scene load_environment_text(std::string_view json_text, const std::string& display_name,
                            const std::string& base_dir = ".");

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

// A planar (2-DOF) environment: the same format with vectors (docs/reference/environments.md, "2-D environments").
// Throws InputError naming the file and the place.
PlanarScene load_planar_environment_file(const std::string& path);
PlanarScene load_planar_environment_text(std::string_view json_text, const std::string& display_name,
                                         const std::string& base_dir = ".");

// A planar environment with its "validate" block over the defaults (the 2-D keys:
// engine/load/validate_block.hpp), for the harness.
struct PlanarEnvironment {
  PlanarScene scene;
  ValidateThresholds validate;
};
PlanarEnvironment load_planar_environment(const std::string& path);
PlanarEnvironment compile_planar_environment(std::string_view json_text, const std::string& display_name,
                                             const std::string& base_dir = ".");

}  // namespace hapscene
