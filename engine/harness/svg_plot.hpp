#pragma once
// Hand-written SVG line charts (no dependency): panels stacked vertically, each with
// axes, "nice" ticks, axis labels with units, a legend, and optional horizontal lines
// (the safety limit).
#include <string>
#include <vector>

namespace hapscene {

struct PlotSeries {
  std::string label;
  std::string color;          // any SVG colour
  std::vector<double> x;
  std::vector<double> y;
  bool dashed{false};
  bool markers{false};        // points as dots, no line (scatter plots)
};

struct PlotLine {
  double y{};
  std::string label;          // shown once in the legend (empty: not shown)
  std::string color{"#c0392b"};
};

struct PlotPanel {
  std::string title;
  std::string x_label;        // with the unit: "position x (mm)"
  std::string y_label;
  std::vector<PlotSeries> series;
  std::vector<PlotLine> lines;
};

// Ticks at 1, 2 or 5 times a power of ten covering [low, high]; also widens the range
// to whole ticks. At least two ticks.
std::vector<double> nice_ticks(double* low, double* high, int target_count = 6);

// At most about `max_points` points, keeping each bucket's minimum and maximum so spikes
// stay visible.
void decimate_min_max(const std::vector<double>& x, const std::vector<double>& y,
                      std::size_t max_points, std::vector<double>* out_x, std::vector<double>* out_y);

// A whole SVG document.
std::string render_svg(const std::string& title, const std::vector<PlotPanel>& panels,
                       int width_px = 900, int panel_height_px = 260);

}  // namespace hapscene
