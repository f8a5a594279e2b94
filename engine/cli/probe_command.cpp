// `hapscene probe ENV --x START:STOP:STEP [--v V] [--t T]`: the open-loop
// force-displacement curve as CSV. force_N is what the environment asks for at (x, v);
// output_N is what the device would be commanded after the static safety rules
// (non-finite -> 0, outside the workspace -> 0, clamp to the force limit). Every point
// is computed from fresh, reset script instances at run time T (default 0), so points
// do not depend on each other or on their order. A row where a script faulted has empty
// force fields (docs/reference/commands.md). Script faults go to stderr, each once
// ("scripts/x.lua:3: message (first at x ...)"), after the CSV; then the exit code is 1.
//
// For a 2-DOF environment (its device a planar profile): `hapscene probe ENV --x
// START:STOP:STEP --y START:STOP:STEP [--v VX,VY]`, one row per grid point (x outer, y
// inner), each shape's proxy at the nearest point of its boundary (open loop).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/planar_open_loop.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

struct ProbeRange {
  double start_m{};
  double stop_m{};
  double step_m{};
  long long points{};
  std::string parts[3];  // as typed
  bool bare{};           // no part has a unit (metres)
};

// "note: --x 0:30:1 is in metres (0 to 30 m), beyond the workspace [-0.05, 0.045] m; did
// you mean 0mm:30mm:1mm?": for a range of plain numbers that does not fit in the device's
// workspace along its axis, where read in mm (or cm) it would. Empty otherwise.
std::string range_unit_note(const std::string& name, const ProbeRange& range, double low_m, double high_m) {
  const double from_m = std::min(range.start_m, range.stop_m);
  const double to_m = std::max(range.start_m, range.stop_m);
  const auto fits = [&](double scale) { return from_m * scale >= low_m && to_m * scale <= high_m; };
  if (!range.bare || fits(1.0)) return "";
  for (const auto& [unit, scale] : {std::pair{"mm", 1e-3}, std::pair{"cm", 1e-2}}) {
    if (!fits(scale)) continue;
    return "note: --" + name + " " + range.parts[0] + ":" + range.parts[1] + ":" + range.parts[2] +
           " is in metres (" + format_number(range.start_m) + " to " + format_number(range.stop_m) +
           " m), beyond the workspace [" + format_number(low_m) + ", " + format_number(high_m) +
           "] m; did you mean " + range.parts[0] + unit + ":" + range.parts[1] + unit + ":" + range.parts[2] + unit +
           "?";
  }
  return "";
}

// --NAME START:STOP:STEP (NAME: x, or y for a planar environment).
ProbeRange parse_range(const Arguments& arguments, const std::string& name, const std::string& text) {
  const std::string option = "--" + name;
  const std::string what = "hapscene probe: " + option;
  const std::size_t first = text.find(':');
  const std::size_t second = first == std::string::npos ? first : text.find(':', first + 1);
  if (second == std::string::npos || text.find(':', second + 1) != std::string::npos) {
    arguments.fail(option + ": expected START:STOP:STEP, got \"" + text + "\"");
  }
  ProbeRange range;
  range.start_m = parse_option_quantity(text.substr(0, first), option::probe_position, what + " START");
  range.stop_m = parse_option_quantity(text.substr(first + 1, second - first - 1), option::probe_position,
                                       what + " STOP");
  range.step_m = parse_option_quantity(text.substr(second + 1), option::probe_step, what + " STEP");
  // Parts with and without a unit in one range: "0:10:1mm" means 0 to 10 m in steps of
  // 1 mm (10 001 points), never what was meant. A bare 0 is the same in every unit.
  const std::string parts[] = {text.substr(0, first), text.substr(first + 1, second - first - 1),
                               text.substr(second + 1)};
  const auto bare_number = [](const std::string& part, double* value) {
    const char* begin = part.data() + (part.starts_with('+') ? 1 : 0);
    const auto [end, ec] = std::from_chars(begin, part.data() + part.size(), *value);
    return ec == std::errc() && end == part.data() + part.size();
  };
  bool any_unit = false;
  std::string bare;
  for (const std::string& part : parts) {
    double value = 0.0;
    if (!bare_number(part, &value)) {
      any_unit = true;
    } else if (value != 0.0 && bare.empty()) {
      bare = part;
    }
  }
  for (int i = 0; i < 3; ++i) range.parts[i] = parts[i];
  range.bare = !any_unit;
  if (any_unit && !bare.empty()) {
    arguments.fail(option + ": \"" + bare + "\" has no unit while another part of \"" + text +
                   "\" has one: give every part its unit (as in 0mm:10mm:1mm), or none for metres");
  }
  if (range.step_m == 0.0) arguments.fail(option + ": STEP must not be 0");
  // A step far below the sensor's resolution is a typo; it would also overflow START / STEP.
  if (std::fabs(range.step_m) < option::kMinProbeStep_m) {
    arguments.fail(option + ": STEP must be at least 1 nm in size, got " + format_number(range.step_m) + " m");
  }
  if ((range.stop_m - range.start_m) * range.step_m < 0.0) {
    arguments.fail(option + ": STEP goes away from STOP");
  }
  // A tolerance of a millionth of a step keeps STOP when rounding falls just short.
  const double intervals = std::floor((range.stop_m - range.start_m) / range.step_m + 1e-6);
  if (intervals + 1.0 > static_cast<double>(option::kMaxProbePoints)) {
    arguments.fail(option + ": more than " + std::to_string(option::kMaxProbePoints) + " points");
  }
  range.points = static_cast<long long>(intervals) + 1;
  return range;
}

// The positions of a range, each the double nearest its decimal value (0.018, not
// 6 x 0.003 = 0.018000000000000002): when START and STEP are whole numbers of 10^-d m for
// some d <= 12, x = (n_start + i n_step) / 10^d, whole numbers divided once, which rounds
// correctly; otherwise x = (start / step + i) * step, round whenever START is a whole
// number of steps.
std::vector<double> range_positions_m(const ProbeRange& range) {
  std::vector<double> x_m(static_cast<std::size_t>(range.points));
  const auto whole = [](double value, double* out) {
    *out = std::round(value);
    return std::fabs(value - *out) <= 1e-9 * std::fabs(*out) && std::fabs(*out) < 1e15;
  };
  double scale = 1.0;
  for (int digits = 0; digits <= 12; ++digits, scale *= 10.0) {
    double step_units = 0.0;
    double start_units = 0.0;
    if (!whole(range.step_m * scale, &step_units) || step_units == 0.0) continue;
    if (range.start_m != 0.0 && !whole(range.start_m * scale, &start_units)) continue;
    for (std::size_t i = 0; i < x_m.size(); ++i) {
      x_m[i] = (start_units + static_cast<double>(i) * step_units) / scale + 0.0;  // no "-0"
    }
    return x_m;
  }
  const double start_in_steps = range.start_m / range.step_m;
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    x_m[i] = (start_in_steps + static_cast<double>(i)) * range.step_m + 0.0;
  }
  return x_m;
}

// The shortest text that reads back as the same double.
std::string shortest(double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::string("nan");
}

// Whether a script faulted at point i: its row's force fields are left empty, so that no
// table shows the 0 N a disabled script answers as if it were the scene's force.
template <int N>
bool faulted_at(const OpenLoopScanOf<N>& scan, std::size_t i) {
  return !scan.script_faulted.empty() && scan.script_faulted[i];
}

// --v VX,VY for a planar environment.
Vec2 parse_planar_velocity(const Arguments& arguments, const std::string& text) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
    arguments.fail("--v: a 2-DOF environment takes VX,VY, got \"" + text + "\"");
  }
  return Vec2{{parse_option_quantity(text.substr(0, comma), option::probe_velocity, "hapscene probe: --v VX"),
               parse_option_quantity(text.substr(comma + 1), option::probe_velocity, "hapscene probe: --v VY")}};
}

// A planar environment's grid: x outer, y inner. The built-in 2-D effects are evaluated
// open loop (no history: each shape's proxy at the nearest point of its boundary).
int probe_planar(const Arguments& arguments, const std::string& file, const std::string& x_text,
                 const std::optional<std::string>& y_text, const std::optional<std::string>& v_text, double t_s) {
  if (!y_text) arguments.fail("--y START:STOP:STEP is required for a 2-DOF environment");
  const ProbeRange x_range = parse_range(arguments, "x", x_text);
  const ProbeRange y_range = parse_range(arguments, "y", *y_text);
  if (static_cast<double>(x_range.points) * static_cast<double>(y_range.points) >
      static_cast<double>(option::kMaxProbePoints)) {
    arguments.fail("--x and --y: more than " + std::to_string(option::kMaxProbePoints) + " points in the grid");
  }
  const Vec2 v_m_per_s = v_text ? parse_planar_velocity(arguments, *v_text) : Vec2{};
  const PlanarScene scene = load_planar_environment_file(file);
  {
    Vec2 low_m;
    Vec2 high_m;
    workspace_bounds(scene.device.limits.workspace, &low_m, &high_m);
    for (const std::string& note : {range_unit_note("x", x_range, low_m[0], high_m[0]),
                                    range_unit_note("y", y_range, low_m[1], high_m[1])}) {
      if (!note.empty()) std::fprintf(stderr, "%s\n", note.c_str());
    }
  }
  const std::vector<double> x_m = range_positions_m(x_range);
  const std::vector<double> y_m = range_positions_m(y_range);
  // Every point as fresh, reset instances give it at run time t (as the 1-D probe's
  // OpenLoop), within the same CPU budget for creating them; each fault once, with the
  // first point (in the order of the output) that met it.
  std::vector<Vec2> points;
  points.reserve(x_m.size() * y_m.size());
  for (const double x : x_m) {
    for (const double y : y_m) points.push_back(Vec2{{x, y}});
  }
  PlanarOpenLoop open_loop(scene, t_s);
  const PlanarOpenLoopScan scan = open_loop.scan(points, v_m_per_s);
  std::string out = "x_m,y_m,vx_m_per_s,vy_m_per_s,force_x_N,force_y_N,output_x_N,output_y_N\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2& force_N = scan.force_N[i];
    const Vec2 output_N = open_loop.output_N(points[i], force_N);
    out += shortest(points[i][0]) + "," + shortest(points[i][1]) + "," + shortest(v_m_per_s[0]) + "," +
           shortest(v_m_per_s[1]) + "," +
           (faulted_at(scan, i) ? std::string(",,,")
                                : shortest(force_N[0]) + "," + shortest(force_N[1]) + "," + shortest(output_N[0]) +
                                      "," + shortest(output_N[1])) +
           "\n";
  }
  write_out(out);
  flush_out();
  if (!scan.behaviour.static_field()) {
    std::fprintf(stderr, "note: %s; each point is from fresh instances at t = %g s\n", scan.behaviour.note.c_str(),
                 t_s);
  }
  const ScriptFaultLog& faults = open_loop.faults();
  for (const std::string& fault : faults.lines()) std::fprintf(stderr, "%s\n", fault.c_str());
  if (faults.omitted()) {
    std::fprintf(stderr, "... and script faults with other messages (only the %zu first in the grid are shown)\n",
                 ScriptFaultLog::kMaxMessages);
  }
  return faults.empty() ? kExitOk : kExitFailure;
}

}  // namespace

int probe_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene probe");
  const std::optional<std::string> x_text = arguments.take_value("x");
  const std::optional<std::string> y_text = arguments.take_value("y");
  const std::optional<std::string> v_text = arguments.take_value("v");
  const double t_s = arguments.take(option::probe_time).value_or(0.0);
  const std::vector<std::string> files = arguments.positionals();
  if (files.size() != 1) arguments.fail("expected one environment file");
  if (!x_text) arguments.fail("--x START:STOP:STEP is required");
  if (environment_axes(files[0]) == 2) return probe_planar(arguments, files[0], *x_text, y_text, v_text, t_s);
  if (y_text) arguments.fail("--y: only for a 2-DOF environment (its device a planar profile)");
  const double v_m_per_s =
      v_text ? parse_option_quantity(*v_text, option::probe_velocity, "hapscene probe: --v") : 0.0;
  const ProbeRange range = parse_range(arguments, "x", *x_text);

  const Scene scene = load_environment_file(files[0]);
  const std::string unit_note =
      range_unit_note("x", range, scene.device.limits.workspace_min_m, scene.device.limits.workspace_max_m);
  if (!unit_note.empty()) std::fprintf(stderr, "%s\n", unit_note.c_str());
  const std::vector<double> x_m = range_positions_m(range);
  OpenLoop open_loop(scene, t_s);
  const OpenLoopScan scan = open_loop.scan(x_m, v_m_per_s);
  std::string out = "x_m,v_m_per_s,force_N,output_N\n";
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    const double force_N = scan.force_N[i];
    out += shortest(x_m[i]) + "," + shortest(v_m_per_s) + "," +
           (faulted_at(scan, i) ? std::string(",")
                                : shortest(force_N) + "," + shortest(open_loop.output_N(x_m[i], force_N))) +
           "\n";
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
