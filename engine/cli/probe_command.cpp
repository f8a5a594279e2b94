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
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "engine/base/axis_columns.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/harness/open_loop.hpp"
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

// The device's workspace box, which --x and --y are compared with (the unit note).
std::pair<double, double> device_workspace_along(const DeviceProfile& device, int /*axis*/) {
  return {device.limits.workspace_min_m, device.limits.workspace_max_m};
}
std::pair<double, double> device_workspace_along(const PlanarProfile& device, int axis) {
  Vec2 low_m;
  Vec2 high_m;
  workspace_bounds(device.limits.workspace, &low_m, &high_m);
  return {low_m[axis], high_m[axis]};
}

// --v: V for one axis; VX,VY (one value per axis, comma-separated) for more.
template <int N>
Axes<N> parse_velocity(const Arguments& arguments, const std::string& text) {
  if constexpr (N == 1) {
    return parse_option_quantity(text, option::probe_velocity, "hapscene probe: --v");
  } else {
    std::string form;
    for (int i = 0; i < N; ++i) form += std::string(i > 0 ? ",V" : "V") + static_cast<char>(std::toupper(kAxisNames[i][0]));
    std::vector<std::string> parts;
    for (std::size_t from = 0;;) {
      const std::size_t comma = text.find(',', from);
      parts.push_back(text.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    if (parts.size() != static_cast<std::size_t>(N)) {
      arguments.fail("--v: a " + std::to_string(N) + "-DOF environment takes " + form + ", got \"" + text + "\"");
    }
    Axes<N> v_m_per_s{};
    for (int i = 0; i < N; ++i) {
      const std::string label = std::string("hapscene probe: --v V") + static_cast<char>(std::toupper(kAxisNames[i][0]));
      v_m_per_s[i] = parse_option_quantity(parts[static_cast<std::size_t>(i)], option::probe_velocity, label);
    }
    return v_m_per_s;
  }
}

// The CSV's header (axis_columns.hpp).
template <int N>
std::string probe_header() {
  return csv_header_line(handle_state_columns<N>()) + "\n";
}

// One value per axis, comma-separated, each the shortest text that reads back.
template <int N>
std::string csv_values(const Axes<N>& value) {
  std::string out;
  for (int i = 0; i < N; ++i) out += (i > 0 ? "," : "") + shortest(component(value, i));
  return out;
}

// The open-loop force at every point of the grid (axis x outer, the last axis inner), as
// CSV on stdout; notes and script faults on stderr. Returns the exit code.
template <int N>
int probe_environment(const Arguments& arguments, const SceneOf<N>& scene, const std::vector<std::string>& range_texts,
                      const std::optional<std::string>& v_text, double t_s) {
  std::vector<ProbeRange> ranges;
  double grid_points = 1.0;
  for (int i = 0; i < N; ++i) {
    ranges.push_back(parse_range(arguments, kAxisNames[i], range_texts[static_cast<std::size_t>(i)]));
    grid_points *= static_cast<double>(ranges.back().points);
  }
  if (N > 1 && grid_points > static_cast<double>(option::kMaxProbePoints)) {
    arguments.fail("--x and --y: more than " + std::to_string(option::kMaxProbePoints) + " points in the grid");
  }
  const Axes<N> v_m_per_s = v_text ? parse_velocity<N>(arguments, *v_text) : Axes<N>{};
  for (int i = 0; i < N; ++i) {
    const auto [low_m, high_m] = device_workspace_along(scene.device, i);
    const std::string note = range_unit_note(kAxisNames[i], ranges[static_cast<std::size_t>(i)], low_m, high_m);
    if (!note.empty()) std::fprintf(stderr, "%s\n", note.c_str());
  }
  // The grid, axis 0 outer.
  std::vector<std::vector<double>> positions_m;
  for (const ProbeRange& range : ranges) positions_m.push_back(range_positions_m(range));
  std::vector<Axes<N>> points;
  points.reserve(static_cast<std::size_t>(grid_points));
  std::vector<std::size_t> index(N, 0);
  while (true) {
    Axes<N> point{};
    if constexpr (N == 1) {
      point = positions_m[0][index[0]];
    } else {
      for (int i = 0; i < N; ++i) point[i] = positions_m[static_cast<std::size_t>(i)][index[static_cast<std::size_t>(i)]];
    }
    points.push_back(point);
    int axis = N - 1;
    while (axis >= 0 && ++index[static_cast<std::size_t>(axis)] == positions_m[static_cast<std::size_t>(axis)].size()) {
      index[static_cast<std::size_t>(axis)] = 0;
      --axis;
    }
    if (axis < 0) break;
  }

  // Every point as fresh, reset instances give it at run time t, within one CPU budget for
  // creating them; each fault once, with the first point (in the order of the output)
  // that met it.
  OpenLoopOf<N> open_loop(scene, t_s);
  const OpenLoopScanOf<N> scan = open_loop.scan(points, v_m_per_s);
  std::string out = probe_header<N>();
  const std::string empty_forces(2 * N - 1, ',');
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Axes<N>& force_N = scan.force_N[i];
    out += csv_values<N>(points[i]) + "," + csv_values<N>(v_m_per_s) + "," +
           (faulted_at(scan, i) ? empty_forces
                                : csv_values<N>(force_N) + "," + csv_values<N>(open_loop.output_N(points[i], force_N))) +
           "\n";
  }
  write_out(out);
  flush_out();

  // What the points mean for scripts with state or time, and every fault, once.
  if (!scan.behaviour.static_field()) {
    std::fprintf(stderr, "note: %s; each point is from fresh instances at t = %g s\n", scan.behaviour.note.c_str(),
                 t_s);
  }
  const ScriptFaultLog& faults = open_loop.faults();
  for (const std::string& line : faults.report_lines(N == 1 ? "in the workspace" : "in the grid")) {
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  return faults.empty() ? kExitOk : kExitFailure;
}

}  // namespace

int probe_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene probe");
  std::vector<std::optional<std::string>> range_texts;
  for (int i = 0; i < kMaxAxes; ++i) range_texts.push_back(arguments.take_value(kAxisNames[i]));
  const std::optional<std::string> v_text = arguments.take_value("v");
  const double t_s = arguments.take(option::probe_time).value_or(0.0);
  const std::vector<std::string> files = arguments.positionals();
  if (files.size() != 1) arguments.fail("expected one environment file");
  if (!range_texts[0]) arguments.fail("--x START:STOP:STEP is required");
  const AnyEnvironment loaded = load_any_environment(files[0]);
  const int axes = axes_of(loaded);
  // One range per axis of the scene: --x, and --y for a 2-DOF environment.
  for (int i = 1; i < kMaxAxes; ++i) {
    const std::string option = std::string("--") + kAxisNames[i];
    if (i < axes && !range_texts[static_cast<std::size_t>(i)]) {
      arguments.fail(option + " START:STOP:STEP is required for a " + std::to_string(axes) + "-DOF environment");
    }
    if (i >= axes && range_texts[static_cast<std::size_t>(i)]) {
      arguments.fail(option + ": only for a 2-DOF environment (its device a planar profile)");
    }
  }
  std::vector<std::string> texts;
  for (int i = 0; i < axes; ++i) texts.push_back(*range_texts[static_cast<std::size_t>(i)]);
  return std::visit(
      [&](const auto& environment) { return probe_environment(arguments, environment.scene, texts, v_text, t_s); },
      loaded);
}

}  // namespace hapscene
