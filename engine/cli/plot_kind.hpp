#pragma once
// `hapscene plot`, per device kind: the figure, drawn as plot_command.cpp (written once
// over N) asks for it. Each kind's function is an overload on its environment type:
// plot_capstan.cpp for one axis (the force-displacement curve and a validate scenario's
// time series), plot_planar.cpp for two (the force field over the workspace, a run's
// paths and its time series per axis). A new kind adds its overload in a file of its own.
#include <cstdint>
#include <optional>
#include <string>

#include "engine/cli/arguments.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

// The options as text, read before the environment's kind is known; each kind reads the
// ones it takes and refuses the others (exit 2).
struct PlotTexts {
  std::optional<std::string> scenario;
  std::optional<std::string> noise;
  std::optional<std::string> start;
  std::optional<std::uint64_t> grid;
  std::optional<std::uint64_t> width;
};

// A kind's figure and what its drawing met.
struct PlotFigure {
  std::string svg;
  ScriptFaultLog faults;    // the field scan's and the run's script faults, each once
  std::string too_slow;     // the "pace" message when the scripts are too slow for the loop
  std::string note;         // said on stderr after the figure (a scenario that does not apply)
  bool nonfinite_seen{};    // the run's safety stage zeroed a non-finite force
};

// The figure of `environment` (loaded from `file`) for the options; fails `arguments`
// (exit 2) on an option the kind refuses; InputError for what the run cannot do.
PlotFigure plot_figure(const Arguments& arguments, const std::string& file, const EnvironmentOf<1>& environment,
                       const PlotTexts& texts, HarnessOptions options);
PlotFigure plot_figure(const Arguments& arguments, const std::string& file, const EnvironmentOf<2>& environment,
                       const PlotTexts& texts, HarnessOptions options);

}  // namespace hapscene
