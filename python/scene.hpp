#pragma once
// hapscene.Scene: an environment file as the engine loaded it (load_environment or
// load_planar_environment, as the command line does), immutable, shared by the calls that
// run it. Its probe() is the command line's `probe` for any points.
#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "engine/load/environment.hpp"

namespace hapscene::python {

namespace py = pybind11;

struct LoadedScene {
  std::string path;  // as given to load()
  int axes{1};
  std::shared_ptr<const Environment> capstan;        // axes == 1
  std::shared_ptr<const PlanarEnvironment> planar;   // axes == 2
};

// Loads `path` as the command line does (its load warnings go to stderr). Throws InputError.
LoadedScene load_scene(const std::string& path);
// hapscene.loads: an environment from JSON text or a dict (relative files from base_dir).
LoadedScene loads_scene(const py::handle& source, const py::object& base_dir, const std::string& name);

// A Scene object, or a path to load (for the functions that take either).
LoadedScene scene_argument(const py::handle& value, const std::string& what);

void bind_scene(py::module_& m);

}  // namespace hapscene::python
