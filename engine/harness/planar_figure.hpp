#pragma once
// The figure of a 2-DOF scene (`hapscene plot` and `run --plot` on a planar scene), one
// self-contained SVG:
// - the force field: the open-loop force (the effects' sum at v = 0, each shape's proxy
//   at the nearest point of its boundary, then the static safety rules: the force limit,
//   nothing outside the workspace) on a grid over the workspace box as arrows centred on
//   their grid points, their length to scale (the largest force one grid cell long) and
//   their colour by magnitude (a colour bar on the right); a grey dot where the force is
//   zero. Drawn over it: the shapes (solid parts shaded, outlines), the workspace (the
//   box dashed, and the profile's polygon when it has one), and a run's handle path and
//   its traced shape's proxy path;
// - below, the run's time series per axis: position (handle and proxy, x and y) and
//   force (commanded, and asked for where the safety rules changed it, x and y, and the
//   commanded magnitude) against time, with the force limit.
#include <string>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/planar_trace.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct PlanarFigureOptions {
  int width_px{900};     // the figure's width
  int grid{24};          // arrows along the workspace box's longer side
};

// The field panel's frame: metres to pixels with one scale on both axes (y up). The
// area drawn is the workspace box widened by 4 % of its size on every side.
struct PlanarFieldView {
  Vec2 min_m{};              // the area drawn
  Vec2 max_m{};
  double left_px{};          // the plot area's top left corner and size
  double top_px{};
  double width_px{};
  double height_px{};
  double scale_px_per_m{};

  double px(double x_m) const noexcept { return left_px + (x_m - min_m[0]) * scale_px_per_m; }
  double py(double y_m) const noexcept { return top_px + (max_m[1] - y_m) * scale_px_per_m; }
};

// The frame of the field panel whose top edge is at panel_top_px.
PlanarFieldView planar_field_view(const PlanarScene& scene, int figure_width_px, double panel_top_px);

// The open-loop field on the grid: `columns` x `rows` points at the centres of equal
// cells covering the workspace box (`grid` along its longer side, at least 2 on the
// other), row by row from the bottom left. Scripts count as the open loop gives them
// (fresh instances at rest, t = 0: PlanarOpenLoop::scan).
struct PlanarFieldGrid {
  int columns{};
  int rows{};
  std::vector<Vec2> points_m;
  std::vector<Vec2> force_N;     // the effects' sum
  std::vector<Vec2> output_N;    // after the static safety rules
  double largest_N{};            // largest |output|
  ScriptFaultLog faults;         // script faults met in the scan, each once with its first point
};
PlanarFieldGrid planar_field_grid(const PlanarScene& scene, int grid);

// The whole figure. `records` (may be empty) is the run drawn, `what` names it ("sweep (a
// raster ...)"), `proxy_label` names the traced proxy ("proxy of the box", "" when none).
// Script faults of the field's scan are added to `faults` (when not null): a figure never
// hides that the field it draws holds the 0 N of a disabled script.
std::string planar_figure_svg(const PlanarScene& scene, const PlanarFigureOptions& options,
                              const std::vector<PlanarTickRecord>& records, const std::string& what,
                              const std::string& proxy_label, ScriptFaultLog* faults = nullptr);

}  // namespace hapscene
