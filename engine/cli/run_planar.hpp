#pragma once
// `hapscene run` settings, and the run of a 2-DOF (planar) environment.
#include <optional>
#include <string>

#include "engine/cli/arguments.hpp"
#include "engine/devices/hapkit_plant.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/run/runner.hpp"

namespace hapscene {

struct RunSettings {
  std::string device{"sim"};
  LinkOptions link;
  RunOptions options;
  SimulationConfig simulation;
  double noise_counts{-1.0};  // < 0: the profile's
  bool quiet{false};
  bool reload{true};          // watch the files and hot-reload them
  std::optional<std::string> log_path;   // --log FILE.csv: per-tick telemetry
  std::optional<std::string> plot_path;  // --plot FILE.svg: the run's time series
  // As given: their meaning depends on the scene's axes (--hold X or --hold X,Y).
  std::optional<std::string> hand_text;
  std::optional<std::string> hold_text;
  std::optional<std::string> start_text;
};

// Runs one planar environment on the simulated 2-DOF device (the only 2-DOF device so far)
// with the options of `hapscene run` that apply: --sim-time, --duration, --log,
// --plot FILE.svg (the figure of engine/harness/planar_figure.hpp),
// --hand none|hold|line|circle|sweep|release|shake, --hold X,Y, --start X,Y (default the
// profile's home), --hand-stiffness, --hand-damping, --release. Returns the exit code.
int run_planar(const Arguments& arguments, const RunSettings& settings, const std::string& file);

}  // namespace hapscene
