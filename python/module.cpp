// The Python module `hapscene` (docs/reference/python.md): the engine's load, probe, simulate,
// validate and test for notebooks and scripts, with numpy arrays in and out. Everything
// runs the command line's code (the hapscene_cli library), so results are the CLI's bit
// for bit. The GIL is released while the engine works; nothing from Python runs in a tick.
#include <pybind11/pybind11.h>

#include "engine/base/errors.hpp"
#include "python/harness.hpp"
#include "python/scene.hpp"
#include "python/simulate.hpp"

namespace py = pybind11;

PYBIND11_MODULE(hapscene, m) {
  m.doc() = R"(hapscene: the haptic rendering engine from Python.

    scene = hapscene.load("environments/wall.json")
    curve = scene.probe(numpy.linspace(-0.01, 0.03, 41))      # the CLI's probe columns
    run = hapscene.simulate(scene, duration="1 s", hand="sweep")  # run --sim-time --log
    report = hapscene.validate(scene)                           # validate --report
    results = hapscene.test(["environments"])                   # test

Invalid input raises hapscene.InputError (a ValueError) with the message the command line
prints after "error: ".)";
  // The CLI's exit code 2: the engine's InputError, message unchanged.
  py::register_exception<hapscene::InputError>(m, "InputError", PyExc_ValueError);
  m.attr("InputError").attr("__doc__") =
      "Invalid input (a file, a value, a script): the message names the place, as the command line prints it.";
  // What the CLI prints on stderr about script faults and script behaviour during a probe.
  m.attr("ScriptFaultWarning") = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("hapscene.ScriptFaultWarning",
                                "A script fault (or a note on a script's state or time) met while probing.",
                                PyExc_RuntimeWarning, nullptr));
  m.attr("__version__") = HAPSCENE_VERSION;
  hapscene::python::bind_scene(m);
  hapscene::python::bind_simulate(m);
  hapscene::python::bind_harness(m);
}
