#pragma once
// The figures hapscene draws: the force-displacement curve of a scene (one curve per
// velocity when an effect reads velocity), and time series of position, velocity and
// force for a run, each with the safety limit drawn.
#include <string>
#include <vector>

#include "engine/harness/open_loop.hpp"
#include "engine/harness/recorder.hpp"
#include "engine/harness/svg_plot.hpp"
#include "engine/harness/validate.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// Force (after the static safety rules) against position across the workspace, every
// 50 um (at most 4001 points), each point from fresh script instances; script faults
// are added to *faults when given.
PlotPanel force_displacement_panel(const Scene& scene, ScriptFaultLog* faults = nullptr);

// Three panels: position, velocity and force against time.
std::vector<PlotPanel> time_series_panels(const Scene& scene, const std::vector<TickRecord>& records,
                                          const std::string& what);

// The force commanded (and the hand's) against the true handle position, tick by tick: a
// run's own force-displacement loop, where hysteresis and limit cycles show.
PlotPanel run_force_position_panel(const Scene& scene, const std::vector<TickRecord>& records,
                                   const std::string& what);

// `hapscene plot`: the force-displacement curve, one scenario's time series and its
// force against position.
std::string scene_figure_svg(const Scene& scene, const ScenarioResult& scenario, ScriptFaultLog* faults = nullptr);

// `validate --plot`: the curve and the first failing scenario (else the first one run).
std::string validation_figure_svg(const Scene& scene, const ValidationReport& report);

// `run --plot`: the curve, the run's time series and its force against position.
std::string run_figure_svg(const Scene& scene, const std::vector<TickRecord>& records,
                           const std::string& what);

}  // namespace hapscene
