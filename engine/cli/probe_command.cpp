// `hapscene probe ENV --x START:STOP:STEP [--v V] [--t T]`: the open-loop
// force-displacement curve as CSV. force_N is what the environment asks for at (x, v);
// output_N is what the device would be commanded after the static safety rules
// (non-finite -> 0, outside the workspace -> 0, clamp to the force limit). Every point
// is computed from fresh, reset script instances at run time T (default 0), so points
// do not depend on each other or on their order. Script faults go to stderr, each once
// ("scripts/x.lua:3: message (first at x ...)"), after the CSV; then the exit code is 1.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

struct ProbeRange {
  double start_m{};
  double stop_m{};
  double step_m{};
  long long points{};
};

ProbeRange parse_range(const Arguments& arguments, const std::string& text) {
  const std::size_t first = text.find(':');
  const std::size_t second = first == std::string::npos ? first : text.find(':', first + 1);
  if (second == std::string::npos || text.find(':', second + 1) != std::string::npos) {
    arguments.fail("--x: expected START:STOP:STEP, got \"" + text + "\"");
  }
  ProbeRange range;
  range.start_m = parse_option_quantity(text.substr(0, first), option::probe_position, "hapscene probe: --x START");
  range.stop_m = parse_option_quantity(text.substr(first + 1, second - first - 1), option::probe_position,
                                       "hapscene probe: --x STOP");
  range.step_m = parse_option_quantity(text.substr(second + 1), option::probe_step, "hapscene probe: --x STEP");
  if (range.step_m == 0.0) arguments.fail("--x: STEP must not be 0");
  // A step far below the sensor's resolution is a typo; it would also overflow START / STEP.
  if (std::fabs(range.step_m) < option::kMinProbeStep_m) {
    arguments.fail("--x: STEP must be at least 1 nm in size, got " + format_number(range.step_m) + " m");
  }
  if ((range.stop_m - range.start_m) * range.step_m < 0.0) {
    arguments.fail("--x: STEP goes away from STOP");
  }
  // A tolerance of a millionth of a step keeps STOP when rounding falls just short.
  const double intervals = std::floor((range.stop_m - range.start_m) / range.step_m + 1e-6);
  if (intervals + 1.0 > static_cast<double>(option::kMaxProbePoints)) {
    arguments.fail("--x: more than " + std::to_string(option::kMaxProbePoints) + " points");
  }
  range.points = static_cast<long long>(intervals) + 1;
  return range;
}

// The shortest text that reads back as the same double.
std::string shortest(double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::string("nan");
}

}  // namespace

int probe_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene probe");
  const std::optional<std::string> x_text = arguments.take_value("x");
  const double v_m_per_s = arguments.take(option::probe_velocity).value_or(0.0);
  const double t_s = arguments.take(option::probe_time).value_or(0.0);
  const std::vector<std::string> files = arguments.positionals();
  if (files.size() != 1) arguments.fail("expected one environment file");
  if (!x_text) arguments.fail("--x START:STOP:STEP is required");
  const ProbeRange range = parse_range(arguments, *x_text);

  const Scene scene = load_environment_file(files[0]);
  // x = (start / step + i) * step lands on round values (0.01, not 0.009999999999999998)
  // whenever start is a whole number of steps.
  const double start_in_steps = range.start_m / range.step_m;
  std::vector<double> x_m(static_cast<std::size_t>(range.points));
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    x_m[i] = (start_in_steps + static_cast<double>(i)) * range.step_m + 0.0;  // no "-0"
  }
  OpenLoop open_loop(scene, t_s);
  const OpenLoopScan scan = open_loop.scan(x_m, v_m_per_s);
  std::string out = "x_m,v_m_per_s,force_N,output_N\n";
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const double force_N = scan.force_N[i];
    out += shortest(x_m[i]) + "," + shortest(v_m_per_s) + "," + shortest(force_N) + "," +
           shortest(open_loop.output_N(x_m[i], force_N)) + "\n";
  }
  write_out(out);
  flush_out();

  // What the points mean for scripts with state or time, and every fault, once.
  if (!scan.behaviour.static_field()) {
    std::fprintf(stderr, "note: %s; each point is from fresh instances at t = %g s\n", scan.behaviour.note.c_str(),
                 t_s);
  }
  for (const std::string& fault : open_loop.faults().lines()) std::fprintf(stderr, "%s\n", fault.c_str());
  if (open_loop.faults().omitted()) {
    std::fprintf(stderr, "... and script faults with other messages (only the %zu first in the workspace are shown)\n",
                 ScriptFaultLog::kMaxMessages);
  }
  return open_loop.faults().empty() ? kExitOk : kExitFailure;
}

}  // namespace hapscene
