// `hapscene plot ENV [--scenario NAME] [--output FILE.svg]`: the force-displacement curve and
// one scenario's time series (default: sweep) as an SVG figure. Script faults met on the
// way (open loop or in the run) go to stderr, each once, after the figure is written;
// then the exit code is 1. So does a failed "pace" check (scripts too slow for the loop,
// seen before the field scan or during the run): its message once, exit 1.
#include <cmath>
#include <cstdio>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/harness_options.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/figures.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

int plot_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene plot");
  HarnessOptions options = take_harness_options(arguments);
  const std::vector<ScenarioKind> kinds = take_scenarios(arguments);
  const std::optional<std::string> out_path = arguments.take_value("output");
  const std::vector<std::string> files = arguments.positionals();
  if (files.size() != 1) arguments.fail("expected one environment file");
  if (kinds.size() > 1) arguments.fail("--scenario: plot draws one scenario");
  if (out_path) {
    const std::string problem = output_path_problem({{"output", *out_path}}, files);
    if (!problem.empty()) arguments.fail(problem);
  }

  const Environment environment = load_environment(files[0]);
  const Scene& scene = environment.scene;
  options.thresholds = environment.validate;
  const ForceField field = probe_force_field(scene, options.thresholds.stiff_threshold_N_per_m);
  const ScenarioKind kind = kinds.empty() ? ScenarioKind::sweep : kinds[0];
  const ScenarioResult result = run_scenario(scene, field, build_scenario(kind, scene, field, options), options);
  // Script faults: the field scan's, the curve's and the run's, each once.
  ScriptFaultLog faults = field.faults;
  const std::string svg = scene_figure_svg(scene, result, &faults);
  for (const auto& fault : result.metrics.script_faults) {
    faults.add(fault.message, fault.where + " of the " + result.scenario.name + " run", INFINITY);
  }
  // Default output: the environment's name with .svg in the working directory.
  const std::string path = out_path.value_or(scene.name + ".svg");
  write_output_file(path, svg);
  print_out("wrote %s\n", printable(path).c_str());
  flush_out();
  // Too slow for the loop: the field scan's verdict, else the run's (one message).
  std::string too_slow = field.too_slow;
  for (const CheckResult& check : result.checks) {
    if (too_slow.empty() && check.name == "pace" && !check.pass) too_slow = check.detail;
  }
  if (!too_slow.empty()) std::fprintf(stderr, "pace: %s\n", too_slow.c_str());
  for (const std::string& fault : faults.lines()) std::fprintf(stderr, "%s\n", fault.c_str());
  if (faults.omitted()) {
    std::fprintf(stderr, "... and script faults with other messages (only the %zu first in the workspace are shown)\n",
                 ScriptFaultLog::kMaxMessages);
  }
  return faults.empty() && too_slow.empty() ? kExitOk : kExitFailure;
}

}  // namespace hapscene
