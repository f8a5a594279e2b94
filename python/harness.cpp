// hapscene.validate() and hapscene.test(): the harness the `validate` and `test` commands
// run, with their reports as Python objects. validate's dict is the JSON `validate
// --report` writes (the same report_to_json, parsed by Python's json module).
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/harness/test_spec.hpp"
#include "engine/harness/validate_kind.hpp"
#include "python/harness.hpp"
#include "python/interruptible.hpp"
#include "python/scene.hpp"
#include "python/values.hpp"

namespace hapscene::python {
namespace {

constexpr const char* kValidate = "hapscene.validate";

// The free scenario's start: a length in 1-D, an (x, y) point in 2-D.
void read_start(const py::object& value, const std::string& what, double* x_m) {
  *x_m = quantity(value, option::free_start, what);
}
void read_start(const py::object& value, const std::string& what, Vec2* x_m) {
  *x_m = point(value, option::run_start, what);
}

// validate on an environment of N axes, its options and scenarios read as that kind
// reads them (engine/harness/validate_kind.hpp), as the CLI does.
template <int N>
nlohmann::json validate_of(const EnvironmentOf<N>& environment, HarnessOptions options, const py::object& scenarios,
                           const py::object& start, const std::string& what) {
  using Kind = ValidateKindOf<N>;
  if (const std::string problem = harness_options_problem<N>(options); !problem.empty()) {
    throw InputError(what + ": " + problem);
  }
  if (!start.is_none()) {
    typename Kind::Point start_m{};
    read_start(start, what + ": start", &start_m);
    Kind::set_free_start(&options, start_m);
  }
  const std::vector<std::string> listed =
      scenarios.is_none() ? std::vector<std::string>{} : names(scenarios, what + ": scenarios");
  if (const std::string problem = scenario_list_problem<N>(listed); !problem.empty()) {
    throw InputError(what + ": scenarios: " + problem);
  }
  const std::vector<ValidateScenarioOf<N>> kinds = scenario_list<N>(listed);
  py::gil_scoped_release release;
  nlohmann::json report;
  run_interruptible([&](const std::atomic<bool>&) { report = report_to_json(validate_environment(environment, kinds, options)); });
  return report;
}

py::object json_object(const nlohmann::json& report) {
  return py::module_::import("json").attr("loads")(report.dump(2));
}

py::object validate(const py::object& scene_value, const py::object& scenarios, const py::object& hand_stiffness,
                    const py::object& hand_damping, const py::object& hand_mass, const py::object& noise,
                    const py::object& seed, const py::object& start) {
  const std::string what = kValidate;
  const LoadedScene loaded = scene_argument(scene_value, what);
  HarnessOptions options;
  options.hand_stiffness_N_per_m =
      optional_quantity(hand_stiffness, option::hand_stiffness, what + ": hand_stiffness").value_or(options.hand_stiffness_N_per_m);
  options.hand_damping_N_s_per_m =
      optional_quantity(hand_damping, option::hand_damping, what + ": hand_damping").value_or(options.hand_damping_N_s_per_m);
  options.hand_mass_kg = optional_quantity(hand_mass, option::hand_mass, what + ": hand_mass").value_or(options.hand_mass_kg);
  options.noise_counts = optional_quantity(noise, option::noise, what + ": noise").value_or(-1.0);
  if (!seed.is_none()) options.seed = whole(seed, option::seed, what + ": seed");

  const nlohmann::json report =
      loaded.visit([&](const auto& environment) { return validate_of(environment, options, scenarios, start, what); });
  return json_object(report);
}

py::list test(const py::object& paths) {
  std::vector<std::string> given;
  if (paths.is_none()) {
    given = {"environments", "scripts"};
  } else if (py::isinstance<py::str>(paths) || py::hasattr(paths, "__fspath__")) {
    given.push_back(path_text(paths, "hapscene.test"));
  } else {
    for (const py::handle item : paths) given.push_back(path_text(item, "hapscene.test"));
  }
  // A folder stands for every *.test.json under it, as on the command line.
  std::vector<std::string> specs;
  for (const std::string& path : given) {
    std::error_code error;
    if (!std::filesystem::is_directory(path, error)) {
      specs.push_back(path);
      continue;
    }
    const std::vector<std::string> found = find_test_specs({path});
    if (found.empty()) throw InputError("hapscene.test: no *.test.json under " + path);
    specs.insert(specs.end(), found.begin(), found.end());
  }
  py::list results;
  for (const std::string& spec : specs) {
    py::dict entry;
    entry["spec"] = spec;
    SpecResult result;
    std::string error;
    {
      py::gil_scoped_release release;
      run_interruptible([&](const std::atomic<bool>&) {
        try {
          result = run_test_spec(spec);
        } catch (const InputError& e) {
          error = e.what();
        }
      });
    }
    if (!error.empty()) {
      entry["environment"] = py::none();
      entry["pass"] = false;
      entry["error"] = error;
      entry["outcomes"] = py::list();
    } else {
      entry["environment"] = result.environment_path;
      entry["pass"] = result.pass;
      entry["error"] = py::none();
      py::list outcomes;
      for (const SpecOutcome& o : result.outcomes) {
        py::dict outcome;
        outcome["what"] = o.what;
        outcome["pass"] = o.pass;
        outcome["message"] = o.message;
        outcomes.append(outcome);
      }
      entry["outcomes"] = outcomes;
    }
    results.append(entry);
  }
  return results;
}

}  // namespace

void bind_harness(py::module_& m) {
  m.def("validate", &validate, py::arg("scene"), py::kw_only(), py::arg("scenarios") = py::none(),
        py::arg("hand_stiffness") = py::none(), py::arg("hand_damping") = py::none(),
        py::arg("hand_mass") = py::none(), py::arg("noise") = py::none(), py::arg("seed") = py::none(),
        py::arg("start") = py::none(),
        R"(validate(scene, *, scenarios=None, hand_stiffness=None, hand_damping=None, hand_mass=None, noise=None, seed=None, start=None) -> dict

Runs the virtual-hand scenarios on the simulated device, as `hapscene validate ENV
--report FILE.json` does, and returns that JSON report as a dict (equal to
json.load() of the CLI's file): "pass", the scene's checks, each scenario's metrics and
checks (e.g. report["scenarios"][i]["metrics"]["passivity_ratio"]).

``scene`` is a path or a hapscene.Scene. ``scenarios``: names or "sweep,press" (default
all: 1-DOF sweep, press, release, hold, shake, free; 2-DOF also swipe). The hand:
hand_stiffness (200 N/m), hand_damping (2 N*s/m), hand_mass (20 g); noise (counts,
1-DOF), seed (1); start: the free scenario's start (1-DOF 4 mm; 2-DOF an (x, y) point,
default the profile's home). The environment's "validate" block sets the thresholds.
Raises hapscene.InputError for invalid input.)");

  m.def("test", &test, py::arg("paths") = py::none(),
        R"(test(paths=None) -> list[dict]

Runs environment test specs (*.test.json) as `hapscene test` does; a folder stands for
every spec under it (default: environments/ and scripts/ of the working directory).
Returns one dict per spec, in order: "spec", "environment", "pass", "error" (the CLI's
message when the spec or its environment is invalid input, else None) and "outcomes"
(each expectation's "what", "pass" and "message").)");
}

}  // namespace hapscene::python
