// hapscene.simulate(): `hapscene run --sim-time --log` in memory. The settings are read
// from Python values with the CLI's option definitions, the device is opened with the
// CLI's open_device, and the run is the CLI's run_watched (engine/cli/recorded_run.hpp),
// so the columns are the --log file's values, bit for bit.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/base/axis_columns.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/planar_run_hand.hpp"
#include "engine/cli/recorded_run.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/devices/virtual_hand.hpp"
#include "python/interruptible.hpp"
#include "python/scene.hpp"
#include "python/simulate.hpp"
#include "python/values.hpp"

namespace hapscene::python {
namespace {

constexpr const char* kWhat = "hapscene.simulate";

// At most this many ticks are kept (about 370 MB of columns): 70 minutes at 1 kHz.
constexpr std::size_t kMaxSimulatedTicks = std::size_t{1} << 22;

struct SimulateArgs {
  py::object duration, hand, hold, start, hand_stiffness, hand_damping, release, noise, seed, device;
};

// The options both axis counts read the same way (run_command's parse_settings).
RunSettings common_settings(const SimulateArgs& a, double rate_hz) {
  RunSettings settings;
  settings.device = a.device.is_none() ? std::string("sim") : py::str(a.device).cast<std::string>();
  if (!(settings.device == "sim" || settings.device == "hil" || settings.device.starts_with("hil:"))) {
    throw InputError(std::string(kWhat) + ": device: \"" + settings.device +
                     "\": simulate runs in simulated time, on \"sim\" or \"hil\" (hil:ELF)");
  }
  settings.options.pacing = Pacing::simulated_time;
  settings.options.duration_s =
      optional_quantity(a.duration, option::duration, std::string(kWhat) + ": duration").value_or(settings.options.duration_s);
  HandConfig& hand = settings.simulation.hand;
  hand.stiffness_N_per_m = optional_quantity(a.hand_stiffness, option::run_hand_stiffness, std::string(kWhat) + ": hand_stiffness")
                               .value_or(hand.stiffness_N_per_m);
  hand.damping_N_s_per_m = optional_quantity(a.hand_damping, option::run_hand_damping, std::string(kWhat) + ": hand_damping")
                               .value_or(hand.damping_N_s_per_m);
  hand.release_s = optional_quantity(a.release, option::release, std::string(kWhat) + ": release").value_or(hand.release_s);
  settings.noise_counts = optional_quantity(a.noise, option::noise, std::string(kWhat) + ": noise").value_or(-1.0);
  if (!a.seed.is_none()) settings.simulation.noise_seed = whole(a.seed, option::seed, std::string(kWhat) + ": seed");
  settings.quiet = true;
  settings.reload = false;  // a loaded Scene is what runs
  const double ticks = std::round(settings.options.duration_s * rate_hz);
  if (ticks > static_cast<double>(kMaxSimulatedTicks)) {
    throw InputError(std::string(kWhat) + ": duration: " + format_number(settings.options.duration_s) + " s at " +
                     format_number(rate_hz) + " Hz is " + format_number(ticks) + " ticks; at most " +
                     std::to_string(kMaxSimulatedTicks) +
                     " are kept in memory (for longer runs: hapscene run --sim-time --log FILE.csv)");
  }
  return settings;
}

template <typename Names>
std::size_t motion_index(const Names& names, const py::object& hand, const std::string& choices) {
  const std::string motion = py::str(hand).cast<std::string>();
  const auto* found = std::find(std::begin(names), std::end(names), motion);
  if (found == std::end(names) || *found == "path") {
    throw InputError(std::string(kWhat) + ": hand: unknown motion \"" + motion + "\" (" + choices + ")");
  }
  return static_cast<std::size_t>(found - std::begin(names));
}

// Columns: double arrays (no "-0", as in the log) and 0/1 arrays.
py::array_t<double> column(std::size_t n, auto&& value_at) {
  py::array_t<double> out(static_cast<py::ssize_t>(n));
  double* data = out.mutable_data();
  for (std::size_t i = 0; i < n; ++i) data[i] = value_at(i) + 0.0;
  return out;
}
py::array_t<std::int8_t> flag_column(std::size_t n, auto&& value_at) {
  py::array_t<std::int8_t> out(static_cast<py::ssize_t>(n));
  std::int8_t* data = out.mutable_data();
  for (std::size_t i = 0; i < n; ++i) data[i] = value_at(i) ? 1 : 0;
  return out;
}

template <int N>
py::dict summary_dict(const SceneOf<N>& scene, const RunSettings& settings, const std::string& hand,
                      const RecordedRunOf<N>& recorded, const std::string& device_report, bool faulted) {
  const RunSummaryOf<N>& s = recorded.run.summary;
  py::dict d;
  d["scene"] = s.scene_name;
  d["source"] = scene.source_path;
  d["device"] = settings.device + ":" + scene.device.name;
  d["rate_hz"] = scene.rate_hz;
  d["pacing"] = "simulated time";
  d["hand"] = hand;
  d["ticks"] = s.ticks;
  d["device_time_s"] = s.device_time_s;
  d["achieved_rate_hz"] = s.achieved_rate_hz;
  d["max_abs_requested_N"] = s.max_abs_requested_N;
  d["max_abs_output_N"] = s.max_abs_output_N;
  d["force_limit_N"] = s.limits_at_end.max_force_N;
  d["clamped_ticks"] = s.safety.clamped_ticks;
  d["slew_limited_ticks"] = s.safety.slew_limited_ticks;
  d["soft_start_ticks"] = s.safety.soft_start_ticks;
  d["outside_workspace_ticks"] = s.safety.outside_workspace_ticks;
  d["position_hold_ticks"] = s.safety.position_hold_ticks;
  if constexpr (N > 1) {
    d["pose_hold_ticks"] = s.safety.pose_hold_ticks;
    d["motor_saturated_ticks"] = s.safety.motor_saturated_ticks;
  }
  d["nonfinite_faults"] = s.safety.nonfinite_faults;
  d["script_errors"] = s.script_errors;
  d["script_budget_overruns"] = s.script_budget_overruns;
  py::list scripts;
  for (const ScriptReport& r : s.scripts) {
    py::dict script;
    script["name"] = r.name;
    script["disabled"] = r.disabled;
    script["fault"] = r.fault;
    script["fault_time_s"] = r.fault_time_s;
    script["skipped_calls"] = r.skipped_calls;
    scripts.append(script);
  }
  d["scripts"] = scripts;
  py::dict compute;
  compute["p50"] = static_cast<double>(s.compute_ns.percentile_ns(0.50)) / 1000.0;
  compute["p99"] = static_cast<double>(s.compute_ns.percentile_ns(0.99)) / 1000.0;
  compute["max"] = static_cast<double>(s.compute_ns.max_ns()) / 1000.0;
  d["tick_compute_us"] = compute;
  d["device_report"] = device_report;
  d["faulted"] = faulted;
  d["exit_code"] = faulted ? kExitFailure : kExitOk;
  return d;
}

// A simulated run's device, per device kind: its options (hand, hold, start, noise) read
// with the GIL held; open() then opens the device without it. hand_name names the hand
// for the summary; counters() are the kind's own summary values, read before the device
// closes.
struct CapstanSimulation {
  DeviceProfile profile;
  SimulationConfig simulation;
  std::string hand_name;
  std::unique_ptr<DeviceOf<1>> open(const RunSettings& settings) const {
    return open_device(settings.device, profile, simulation, settings.link);
  }
  static std::vector<std::pair<const char*, std::uint64_t>> counters(const DeviceOf<1>& /*device*/) { return {}; }
};

CapstanSimulation simulation_of(const SceneOf<1>& scene, const SimulateArgs& a, const RunSettings& settings) {
  CapstanSimulation out{scene.device, settings.simulation, {}};
  HandConfig& hand = out.simulation.hand;
  if (!a.hand.is_none()) {
    hand.motion = static_cast<HandMotion>(
        motion_index(kHandMotionNames, a.hand, "use sweep, hold, release, shake or none"));
  }
  if (!a.hold.is_none()) hand.hold_m = quantity(a.hold, option::hold, std::string(kWhat) + ": hold");
  if (!a.start.is_none()) out.simulation.start_x_m = quantity(a.start, option::run_start, std::string(kWhat) + ": start");
  if (settings.noise_counts >= 0.0) out.profile.plant.sensor_noise_counts = settings.noise_counts;
  out.hand_name = kHandMotionNames[static_cast<int>(hand.motion)];
  return out;
}

struct PlanarSimulation {
  const PlanarProfile* profile{};
  PlanarSimulationConfig simulation;
  Vec2 start_m{};
  std::string hand_name;
  std::unique_ptr<DeviceOf<2>> open(const RunSettings& settings) {
    try {
      simulation.start_q_rad = planar_joint_angles_at(*profile, start_m);
    } catch (const InputError& error) {
      throw InputError(std::string("start: ") + error.what());  // simulate_of names the function
    }
    return open_planar_device(settings.device, *profile, simulation, settings.link);
  }
  static std::vector<std::pair<const char*, std::uint64_t>> counters(const DeviceOf<2>& device) {
    const PlanarPlant* plant = simulated_planar_plant(device);
    return {{"plant_linkage_faults", plant != nullptr ? plant->linkage_faults() : 0}};
  }
};

PlanarSimulation simulation_of(const SceneOf<2>& scene, const SimulateArgs& a, const RunSettings& settings) {
  if (settings.noise_counts >= 0.0) throw InputError(std::string(kWhat) + ": noise: not yet for a 2-DOF environment");
  if (settings.device != "sim") {
    throw InputError(std::string(kWhat) + ": device: a 2-DOF scene runs in simulated time on \"sim\" only");
  }
  PlanarSimulation out;
  out.profile = &scene.device;
  out.start_m = a.start.is_none() ? scene.device.home_m : point(a.start, option::run_start, std::string(kWhat) + ": start");
  PlanarHandMotion motion = PlanarHandMotion::sweep;
  if (!a.hand.is_none()) {
    motion = static_cast<PlanarHandMotion>(motion_index(
        kPlanarHandMotionNames, a.hand, "a 2-DOF run takes sweep, line, circle, hold, release, shake or none"));
  }
  const Vec2 hold_m = a.hold.is_none() ? out.start_m : point(a.hold, option::hold, std::string(kWhat) + ": hold");
  out.simulation.hand = planar_run_hand(scene, motion, settings.simulation.hand, hold_m);
  out.simulation.noise_seed = settings.simulation.noise_seed;
  out.hand_name = kPlanarHandMotionNames[static_cast<int>(motion)];
  return out;
}

// Every tick's values as numpy arrays, named as the log's columns (telemetry_log.hpp),
// then the simulator's true state per axis: x_true_m, v_true_m_per_s, motor_force_N,
// hand_force_N (1-D); x_true_m, y_true_m, vx_true_m_per_s, ..., hand_force_y_N (2-D).
template <int N>
void add_columns(const RecordedRunOf<N>& recorded, py::dict* out) {
  using Sample = TelemetrySampleOf<N>;
  using Truth = TruthSampleOf<N>;
  const auto& v = recorded.samples;
  const auto& t = recorded.truths;
  const std::size_t n = v.size();
  const std::vector<std::string> logged = telemetry_columns<N>();
  std::size_t c = 0;
  (*out)[logged[c++].c_str()] = column(n, [&](std::size_t i) { return v[i].t_s; });
  for (Axes<N> Sample::*quantity : {&Sample::x_m, &Sample::v_m_per_s, &Sample::force_N, &Sample::output_N}) {
    for (int k = 0; k < N; ++k) (*out)[logged[c++].c_str()] = column(n, [&](std::size_t i) { return component(v[i].*quantity, k); });
  }
  for (int k = 0; k < N; ++k) {
    (*out)[logged[c++].c_str()] = column(n, [&](std::size_t i) { return motor_of(v[i].command, k).duty; });
    (*out)[logged[c++].c_str()] = flag_column(n, [&](std::size_t i) { return motor_of(v[i].command, k).direction_high; });
  }
  const std::vector<std::string> truths =
      axis_columns<N>({{"", "_true_m"}, {"v", "_true_m_per_s"}, {"motor_force_", "_N"}, {"hand_force_", "_N"}});
  c = 0;
  for (Axes<N> Truth::*quantity : {&Truth::x_m, &Truth::v_m_per_s, &Truth::motor_force_N, &Truth::hand_force_N}) {
    for (int k = 0; k < N; ++k) (*out)[truths[c++].c_str()] = column(n, [&](std::size_t i) { return component(t[i].*quantity, k); });
  }
}

// `hapscene run --sim-time --log` of a scene with N axes, in memory.
template <int N>
py::dict simulate_of(const EnvironmentOf<N>& environment, const std::string& path, const SimulateArgs& a) {
  const SceneOf<N>& scene = environment.scene;
  RunSettings settings = common_settings(a, scene.rate_hz);
  auto simulation = simulation_of(scene, a, settings);

  RecordedRunOf<N> recorded;
  std::string report;
  bool faulted = false;
  std::vector<std::pair<const char*, std::uint64_t>> counters;
  {
    py::gil_scoped_release release;
    std::unique_ptr<DeviceOf<N>> device;
    try {
      device = simulation.open(settings);
    } catch (const InputError& error) {
      throw InputError(std::string(kWhat) + ": " + error.what());
    }
    run_interruptible([&](const std::atomic<bool>& stop) {
      settings.options.stop_requested = &stop;
      recorded = record_run<N>(scene, *device, path, settings);
    });
    report = device->report();
    counters = simulation.counters(*device);
    faulted = run_faulted(recorded.run, *device);
  }
  if (recorded.dropped > 0) throw std::runtime_error("hapscene.simulate: the run went past its reservation");
  py::dict out;
  add_columns<N>(recorded, &out);
  py::dict summary = summary_dict<N>(scene, settings, simulation.hand_name, recorded, report, faulted);
  for (const auto& [name, count] : counters) summary[name] = count;
  out["summary"] = summary;
  return out;
}

constexpr const char* kSimulateDoc = R"(simulate(scene, *, duration=None, hand=None, hold=None, start=None, hand_stiffness=None, hand_damping=None, release=None, noise=None, seed=None, device="sim") -> dict

Runs an environment in simulated time as `hapscene run ENV --sim-time --log FILE.csv`
does, with the same options, and returns every tick's values, bit for bit the log's.

``scene`` is a path or a hapscene.Scene. Options (None: the CLI's default; numbers in SI
or strings with units, "3 s", "20 mm"):

- duration: device time (default 2 s)
- hand: "sweep" (default), "hold", "release", "shake", "none"; 2-DOF also "line", "circle"
- hold, start: positions (2-DOF: (x, y) points; start defaults to the profile's home)
- hand_stiffness, hand_damping, release: the simulated hand (200 N/m, 2 N*s/m, 0.5 s)
- noise: sensor noise in counts (default the profile's; 1-DOF only); seed: its seed (1)
- device: "sim" (default) or "hil" (the firmware on a simulated ATmega328P; 1-DOF)

Returns a dict of numpy arrays, one per tick: the log's columns (1-DOF: t_s, x_m,
v_m_per_s, force_N, output_N, duty, direction; 2-DOF: t_s, x_m, y_m, vx_m_per_s,
vy_m_per_s, force_x_N, force_y_N, output_x_N, output_y_N, duty_1, direction_1, duty_2,
direction_2), then the simulator's true state (x_true_m, v_true_m_per_s, motor_force_N,
hand_force_N; 2-DOF: per axis, x_true_m, y_true_m, vx_true_m_per_s, ...), and "summary":
the run summary the CLI prints, as a dict (ticks, max forces, safety counters, scripts,
tick compute time, the device's report, "exit_code": what `run` would exit with).

The run happens without the GIL; nothing from Python runs inside a tick. Ctrl-C (a
notebook's interrupt) stops it within 20 ms and raises KeyboardInterrupt. Raises
hapscene.InputError for invalid values, with the CLI's range in the message.)";

}  // namespace

void bind_simulate(py::module_& m) {
  m.def(
      "simulate",
      [](const py::object& scene, const py::object& duration, const py::object& hand, const py::object& hold,
         const py::object& start, const py::object& hand_stiffness, const py::object& hand_damping,
         const py::object& release, const py::object& noise, const py::object& seed, const py::object& device) {
        const LoadedScene loaded = scene_argument(scene, kWhat);
        const SimulateArgs args{duration, hand, hold, start, hand_stiffness, hand_damping, release, noise, seed, device};
        return loaded.visit([&](const auto& environment) { return simulate_of(environment, loaded.path, args); });
      },
      py::arg("scene"), py::kw_only(), py::arg("duration") = py::none(), py::arg("hand") = py::none(),
      py::arg("hold") = py::none(), py::arg("start") = py::none(), py::arg("hand_stiffness") = py::none(),
      py::arg("hand_damping") = py::none(), py::arg("release") = py::none(), py::arg("noise") = py::none(),
      py::arg("seed") = py::none(), py::arg("device") = "sim", kSimulateDoc);
}

}  // namespace hapscene::python
