#pragma once
// The summary `hapscene run` prints after each environment's run, written once for any
// number of axes. The lines are the same for every N where they mean the same; with more
// than one axis, forces are magnitudes, the workspace bounds are per axis, the linkage's
// counters get a line of their own, and a disabled script says where the handle was.
#include <string_view>

#include "engine/cli/run_settings.hpp"
#include "engine/run/runner.hpp"
#include "engine/run/script_fault_places.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

// `hand`: the hand's motion as named on the command line. `places`: where each script of
// the scene running at the end faulted (may be null; used with more than one axis).
template <int N>
void print_run_summary(const SceneOf<N>& scene, const RunSettings& settings, std::string_view hand,
                       const RunSummaryOf<N>& summary, const ScriptFaultPlaces<N>* places);

}  // namespace hapscene
