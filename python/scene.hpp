#pragma once
// hapscene.Scene: an environment file as the engine loaded it (load_any_environment, as
// the command line does), immutable, shared by the calls that run it. Its probe() is the command line's `probe` for any points.
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <utility>
#include <variant>

#include "engine/load/environment.hpp"

namespace hapscene::python {

namespace py = pybind11;

struct LoadedScene {
  std::string path;  // as given to load()
  // The environment of the N its device has, parsed once (engine/load/environment.hpp).
  std::shared_ptr<const AnyEnvironment> environment;

  int axes() const { return axes_of(*environment); }
  template <int N>
  const EnvironmentOf<N>& of() const { return std::get<EnvironmentOf<N>>(*environment); }
  // f(environment), with the environment of its N: code written once over N.
  template <typename F>
  decltype(auto) visit(F&& f) const { return std::visit(std::forward<F>(f), *environment); }
};

// Loads `path` as the command line does (its load warnings go to stderr). Throws InputError.
LoadedScene load_scene(const std::string& path);
// hapscene.loads: an environment from JSON text or a dict (relative files from base_dir).
LoadedScene loads_scene(const py::handle& source, const py::object& base_dir, const std::string& name);

// A Scene object, or a path to load (for the functions that take either).
LoadedScene scene_argument(const py::handle& value, const std::string& what);

void bind_scene(py::module_& m);

}  // namespace hapscene::python
