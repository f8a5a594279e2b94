#include "python/scene.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/base/axis_columns.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/harness/open_loop.hpp"
#include "python/interruptible.hpp"
#include "python/values.hpp"

namespace hapscene::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// One compiled effect as a dict: its type and the values it was compiled with, in SI
// (the names carry the units), as its declaration lists them
// (engine/effects/effect_keys.hpp): numbers as floats, vectors as (x, y) tuples, choices
// and flags as bools. A new effect type shows its keys without a change here.
template <typename Effect>
py::dict effect_dict(const Effect& e) {
  py::dict d;
  d["type"] = Effect::kType;
  if constexpr (requires { Effect::keys(); }) {
    for (const KeyOf<Effect>& bound : Effect::keys()) {
      const EffectKey& key = bound.key;
      if (key.field.empty()) continue;
      const std::string field(key.field);
      if (const bool* flag = read_flag(bound, e)) {
        d[field.c_str()] = py::bool_(*flag);
      } else if (const double* numbers = read_numbers(bound, e)) {
        const int count = component_count(key, Effect::kAxes);
        if (count == 1) {
          d[field.c_str()] = py::float_(numbers[0]);
        } else {
          py::tuple values(static_cast<std::size_t>(count));
          for (int i = 0; i < count; ++i) values[static_cast<std::size_t>(i)] = py::float_(numbers[i]);
          d[field.c_str()] = values;
        }
      }
    }
  }
  if constexpr (requires { e.program; }) {
    d["name"] = e.program->display_name;
    d["file"] = e.file;
    py::dict params;
    for (const ScriptParam& p : e.program->params) {
      if (p.kind == ScriptParam::Kind::number) params[p.name.c_str()] = p.value_si;
      else if (p.kind == ScriptParam::Kind::boolean) params[p.name.c_str()] = p.flag;
      else params[p.name.c_str()] = p.text;
    }
    d["params"] = params;
  }
  return d;
}

template <int N>
py::list effect_list(const SceneOf<N>& scene) {
  py::list list;
  for (const auto& effect : scene.effects) {
    list.append(std::visit([](const auto& e) { return effect_dict(e); }, effect));
  }
  return list;
}

// Every number of every effect, flat: "effects[0].stiffness_N_per_m", and a script's
// parameters as "effects[2].params.height" (SI). Points give ".x" and ".y" entries.
py::dict flat_parameters(const py::list& effects) {
  py::dict flat;
  for (std::size_t i = 0; i < effects.size(); ++i) {
    const std::string prefix = "effects[" + std::to_string(i) + "].";
    const auto add = [&flat](const std::string& key, const py::handle& value) {
      if (py::isinstance<py::float_>(value)) {
        flat[key.c_str()] = value;
      } else if (py::isinstance<py::tuple>(value) && py::len(value) == 2) {
        flat[(key + ".x").c_str()] = value[py::int_(0)];
        flat[(key + ".y").c_str()] = value[py::int_(1)];
      }
    };
    for (const auto& [key, value] : effects[i].cast<py::dict>()) {
      const std::string name = key.cast<std::string>();
      if (name == "params") {
        for (const auto& [param, param_value] : value.cast<py::dict>()) {
          add(prefix + "params." + param.cast<std::string>(), param_value);
        }
      } else {
        add(prefix + name, value);
      }
    }
  }
  return flat;
}

template <int N>
const SceneOf<N>& compiled(const LoadedScene& s) {
  return s.of<N>().scene;
}

// Script faults and what the points mean, as the CLI prints them on stderr: here Python
// warnings (hapscene.ScriptFaultWarning), one per line.
// `among`: where the points were, as the CLI's probe says it ("in the workspace", "in the grid").
void warn_lines(const ScriptBehaviour& behaviour, double t_s, const ScriptFaultLog& faults, std::string_view among) {
  const py::object warn = py::module_::import("warnings").attr("warn");
  const py::object category = py::module_::import("hapscene").attr("ScriptFaultWarning");
  if (!behaviour.static_field()) {
    warn(printf_string("note: %s; each point is from fresh instances at t = %g s", behaviour.note.c_str(), t_s),
         category, 2);
  }
  for (const std::string& line : faults.report_lines(among)) warn(line, category, 2);
}

void check_points(std::size_t points) {
  if (points > static_cast<std::size_t>(option::kMaxProbePoints)) {
    throw InputError("Scene.probe: more than " + std::to_string(option::kMaxProbePoints) + " points");
  }
}

// Every value of `values` in `option`'s range (as --x START and STOP are).
void check_range(const double* values, std::size_t n, const QuantityOption& option, const std::string& what) {
  for (std::size_t i = 0; i < n; ++i) {
    const double v = values[i];
    if (!std::isfinite(v) || v < option.min || v > option.max) {
      throw InputError("Scene.probe: " + what + "[" + std::to_string(i) + "]: must be in " + describe_range(option) +
                       ", got " + format_number(v));
    }
  }
}

Array array_like(const Array& shape_of, const std::vector<double>& values) {
  Array out(std::vector<py::ssize_t>(shape_of.shape(), shape_of.shape() + shape_of.ndim()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// The open-loop force at each point (coordinates[k]: axis k of every point, all of one
// shape), as the CLI's probe computes it: one column per axis and quantity
// (axis_columns.hpp), each shaped like the coordinates.
template <int N>
py::dict probe_scene(const LoadedScene& s, const std::array<Array, N>& coordinates, const Axes<N>& v_m_per_s,
                     double t_s) {
  const SceneOf<N>& scene = compiled<N>(s);
  const Array& shape = coordinates[0];
  std::vector<Axes<N>> points(static_cast<std::size_t>(shape.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if constexpr (N == 1) {
      points[i] = coordinates[0].data()[i];
    } else {
      for (int k = 0; k < N; ++k) points[i][k] = coordinates[static_cast<std::size_t>(k)].data()[i];
    }
  }
  // Position, velocity, asked force, commanded force: N columns each.
  std::vector<double> columns[4 * N];
  for (auto& column : columns) column.resize(points.size());
  ScriptBehaviour behaviour;
  ScriptFaultLog faults;
  {
    py::gil_scoped_release release;
    run_interruptible([&](const std::atomic<bool>&) {
      OpenLoopOf<N> open_loop(scene, t_s);
      const OpenLoopScanOf<N> scan = open_loop.scan(points, v_m_per_s);
      for (std::size_t i = 0; i < points.size(); ++i) {
        const Axes<N>& force_N = scan.force_N[i];
        const Axes<N> output_N = open_loop.output_N(points[i], force_N);
        // Where a script faulted: NaN, not the 0 N a disabled script answers (as the CSV's empty fields).
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const bool faulted = !scan.script_faulted.empty() && scan.script_faulted[i];
        for (int k = 0; k < N; ++k) {
          columns[k][i] = component(points[i], k);
          columns[N + k][i] = component(v_m_per_s, k);
          columns[2 * N + k][i] = faulted ? nan : component(force_N, k);
          columns[3 * N + k][i] = faulted ? nan : component(output_N, k);
        }
      }
      behaviour = scan.behaviour;
      faults = open_loop.faults();
    });
  }
  warn_lines(behaviour, t_s, faults, N == 1 ? "in the workspace" : "in the grid");
  const std::vector<std::string> names = handle_state_columns<N>();
  py::dict out;
  for (std::size_t c = 0; c < names.size(); ++c) out[names[c].c_str()] = array_like(shape, columns[c]);
  return out;
}

double probe_scalar(const py::object& value, const QuantityOption& option, const std::string& what) {
  return quantity(value, option, "Scene.probe: " + what);
}

py::dict probe(const LoadedScene& s, const py::object& x, const py::object& y, const py::object& v,
               const py::object& vx, const py::object& vy, const py::object& t) {
  const double t_s = probe_scalar(t, option::probe_time, "t");
  if (s.axes() == 1) {
    if (!y.is_none()) throw InputError("Scene.probe: y: only for a 2-DOF environment (its device a planar profile)");
    if (!vx.is_none() || !vy.is_none()) throw InputError("Scene.probe: vx, vy: only for a 2-DOF environment; use v");
    const Array xs = Array::ensure(x);
    if (!xs) throw InputError("Scene.probe: x: expected numbers (a float or an array)");
    check_points(static_cast<std::size_t>(xs.size()));
    check_range(xs.data(), static_cast<std::size_t>(xs.size()), option::probe_position, "x");
    return probe_scene<1>(s, {xs}, v.is_none() ? 0.0 : probe_scalar(v, option::probe_velocity, "v"), t_s);
  }
  if (y.is_none()) throw InputError("Scene.probe: y is required for a 2-DOF environment");
  if (!v.is_none()) throw InputError("Scene.probe: v: a 2-DOF environment takes vx and vy");
  const py::tuple both = py::module_::import("numpy").attr("broadcast_arrays")(x, y);
  const Array xs = Array::ensure(both[0]);
  const Array ys = Array::ensure(both[1]);
  if (!xs || !ys) throw InputError("Scene.probe: x, y: expected numbers (floats or arrays)");
  check_points(static_cast<std::size_t>(xs.size()));
  check_range(xs.data(), static_cast<std::size_t>(xs.size()), option::probe_position, "x");
  check_range(ys.data(), static_cast<std::size_t>(ys.size()), option::probe_position, "y");
  const Vec2 v_m_per_s{{vx.is_none() ? 0.0 : probe_scalar(vx, option::probe_velocity, "vx"),
                        vy.is_none() ? 0.0 : probe_scalar(vy, option::probe_velocity, "vy")}};
  return probe_scene<2>(s, {xs, ys}, v_m_per_s, t_s);
}

constexpr const char* kProbeDoc = R"(probe(x, y=None, *, v=None, vx=None, vy=None, t=0.0) -> dict[str, numpy.ndarray]

The open-loop force at each point, as `hapscene probe` computes it (bit for bit).

1-DOF scene: ``x`` (m, a float or an array of any shape) and the velocity ``v`` (m/s,
default 0). Returns the CLI's columns ``x_m``, ``v_m_per_s``, ``force_N`` (what the
effects ask for) and ``output_N`` (after the static safety rules), each an array of x's
shape.

2-DOF scene: ``x`` and ``y`` (broadcast together, e.g. from numpy.meshgrid) and ``vx``,
``vy``. Returns ``x_m``, ``y_m``, ``vx_m_per_s``, ``vy_m_per_s``, ``force_x_N``,
``force_y_N``, ``output_x_N``, ``output_y_N``.

Every point comes from fresh script instances at run time ``t`` (s), so points do not
depend on each other. Script faults and notes (what the CLI prints on stderr) are issued
as hapscene.ScriptFaultWarning warnings. Values may be numbers in SI or strings with
units ("5 mm"). Raises hapscene.InputError for values outside the CLI's ranges or more
than 1000000 points, RuntimeError with the "too slow for the loop" message when the
scripts' calls take more than a tenth of the tick period each (as `hapscene probe` exits
1), and KeyboardInterrupt on Ctrl-C, within a few script calls.)";

}  // namespace

LoadedScene load_scene(const std::string& path) {
  LoadedScene s;
  s.path = path;
  py::gil_scoped_release release;
  s.environment = std::make_shared<const AnyEnvironment>(load_any_environment(path));
  return s;
}

LoadedScene loads_scene(const py::handle& source, const py::object& base_dir_value, const std::string& name) {
  const std::string base_dir = path_text(base_dir_value, "hapscene.loads: base_dir");
  std::string text;
  if (py::isinstance<py::str>(source)) {
    text = source.cast<std::string>();
  } else if (py::isinstance<py::dict>(source)) {
    // The dict as JSON (what json.dumps makes of it: a value JSON has no form for is refused).
    try {
      text = py::module_::import("json").attr("dumps")(source, py::arg("allow_nan") = false).cast<std::string>();
    } catch (py::error_already_set& error) {
      throw InputError("hapscene.loads: " + name + ": not JSON: " + std::string(py::str(error.value())));
    }
  } else {
    throw InputError("hapscene.loads: expected a JSON string or a dict, got " +
                     std::string(py::str(py::type::of(source).attr("__name__"))));
  }
  LoadedScene s;
  s.path = name;
  {
    py::gil_scoped_release release;
    s.environment = std::make_shared<const AnyEnvironment>(compile_any_environment(text, name, base_dir));
  }
  // Its load warnings on stderr, as load() and the command line print a file's.
  for (const std::string& warning : s.visit([](const auto& e) { return e.scene.load_warnings; })) {
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  }
  return s;
}

// Every built-in effect type's declaration (engine/effects/effect_keys.hpp), for tools
// that build forms or check files: [{"type", "axes", "description", "keys": [...]}].
py::list effect_types() {
  py::list out;
  const auto add = [&](const EffectDeclaration& declaration) {
    py::list keys;
    for (const EffectKey& key : declaration.keys) {
      if (key.form == KeyForm::refused) continue;
      py::dict k;
      k["name"] = std::string(key.name);
      k["form"] = std::string(form_name(key.form));
      k["quantity"] = std::string(quantity_name(key.quantity));
      k["unit"] = std::string(si_unit(key.quantity));
      k["required"] = key.required;
      const bool numbers = key.form == KeyForm::number || key.form == KeyForm::vector || key.form == KeyForm::points ||
                           key.form == KeyForm::friction;
      if (numbers) {
        k["min"] = key.range.min;
        k["min_excluded"] = key.range.min_excluded;
        k["max"] = key.range.max;
      }
      if (key.form == KeyForm::points) {
        k["min_items"] = key.min_items;
        k["max_items"] = key.max_items;
      }
      if (!key.required && !key.fallback_from.empty()) k["default_from"] = std::string(key.fallback_from);
      else if (!key.required && (key.form == KeyForm::number || key.form == KeyForm::vector)) k["default"] = key.fallback_si;
      else if (!key.required && key.form == KeyForm::flag) k["default"] = key.fallback_si != 0.0;
      if (key.form == KeyForm::choice) k["choices"] = py::make_tuple(std::string(key.choices[0]), std::string(key.choices[1]));
      k["slidable"] = key.slidable;
      k["field"] = key.field.empty() ? py::object(py::none()) : py::object(py::str(std::string(key.field)));
      k["description"] = std::string(key.description);
      keys.append(k);
    }
    py::dict d;
    d["type"] = std::string(declaration.type);
    d["axes"] = declaration.axes;
    d["description"] = std::string(declaration.description);
    d["keys"] = keys;
    out.append(d);
  };
#define HAPSCENE_PYTHON_EFFECT_TYPES(N) \
  for (const EffectDeclaration& declaration : SceneParts<N>::Effects::kDeclarations) add(declaration);
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_PYTHON_EFFECT_TYPES)
#undef HAPSCENE_PYTHON_EFFECT_TYPES
  return out;
}

LoadedScene scene_argument(const py::handle& value, const std::string& what) {
  if (py::isinstance<LoadedScene>(value)) return value.cast<LoadedScene>();
  return load_scene(path_text(value, what));
}

void bind_scene(py::module_& m) {
  py::class_<LoadedScene>(m, "Scene", R"(An environment as the engine loaded it (hapscene.load(path)).

Immutable; pass it to simulate() and validate() to run the loaded version without reading
the file again.)")
      .def_property_readonly("path", [](const LoadedScene& s) { return s.path; }, "The file it was loaded from.")
      .def_property_readonly("name", [](const LoadedScene& s) { return s.visit([](const auto& e) { return e.scene.name; }); },
                             "The environment's name.")
      .def_property_readonly("rate", [](const LoadedScene& s) { return s.visit([](const auto& e) { return e.scene.rate_hz; }); },
                             "The tick rate in Hz.")
      .def_property_readonly("axes", [](const LoadedScene& s) { return s.axes(); }, "1 (the Hapkit) or 2 (a planar device).")
      .def_property_readonly("device", [](const LoadedScene& s) { return s.visit([](const auto& e) { return e.scene.device.name; }); },
                             "The device profile's name (\"hapkit3\").")
      .def_property_readonly("effects", [](const LoadedScene& s) { return s.visit([](const auto& e) { return effect_list(e.scene); }); },
                             "The compiled effects in file order (disabled ones are left out): one dict each, "
                             "its \"type\" and its parameters in SI (names carry the units; points are (x, y)).")
      .def_property_readonly("parameters", [](const LoadedScene& s) {
            // Read-only (a Scene is immutable): assigning raises TypeError instead of
            // changing a copy nobody reads.
            const py::dict flat = flat_parameters(s.visit([](const auto& e) { return effect_list(e.scene); }));
            return py::module_::import("types").attr("MappingProxyType")(flat);
          },
          "Every numeric parameter of the effects, flat and read-only: {\"effects[0].stiffness_N_per_m\": 500.0, ...}; "
          "script parameters as \"effects[i].params.NAME\". To change one, edit the environment's dict and "
          "hapscene.loads() it.")
      .def_property_readonly("load_warnings", [](const LoadedScene& s) {
            return s.visit([](const auto& e) { return e.scene.load_warnings; });
          },
          "The load warnings (the CLI prints them on stderr as \"warning: ...\").")
      .def("probe", &probe, py::arg("x"), py::arg("y") = py::none(), py::kw_only(), py::arg("v") = py::none(),
           py::arg("vx") = py::none(), py::arg("vy") = py::none(), py::arg("t") = 0.0, kProbeDoc)
      .def("__repr__", [](const LoadedScene& s) {
        const std::string name = s.visit([](const auto& e) { return e.scene.name; });
        return "<hapscene.Scene " + name + " from " + s.path + ", " + std::to_string(s.axes()) + " axis" +
               (s.axes() == 1 ? "" : "es") + ">";
      });

  m.def("effect_types", &effect_types,
        "Every built-in effect type of every number of axes as the engine declares it: its \"type\", \"axes\", "
        "\"description\" and \"keys\" (each key's name, form, quantity and SI unit, whether it is required, its "
        "range, default, whether the live view slides it, and the name of its compiled value in Scene.effects).");
  m.def("load", [](const py::object& path) { return load_scene(path_text(path, "hapscene.load")); }, py::arg("path"),
        R"(load(path) -> Scene

Loads an environment file (JSON, or a .lua script) as `hapscene run` does: every value
checked, scripts compiled. Load warnings go to stderr, as on the command line.

Raises hapscene.InputError with the CLI's located message
("environments/x.json: /effects/0/stiffness: must be in ...").)");

  m.def("loads", &loads_scene, py::arg("source"), py::kw_only(), py::arg("base_dir") = py::str("."),
        py::arg("name") = "<string>",
        R"(loads(source, *, base_dir=".", name="<string>") -> Scene

Loads an environment from JSON text or a dict (as json.loads gives it), checked and
compiled as load() does a file: a sweep needs no temporary files. Script files and device
profiles named in it are found from ``base_dir``; ``name`` names it in messages
("<string>: /effects/0/stiffness: must be in ...") and is the Scene's path.

Raises hapscene.InputError with the located message, also for a dict json.dumps cannot
write (NaN, a set).)");
}

}  // namespace hapscene::python
