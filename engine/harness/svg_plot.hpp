#pragma once
// Hand-written SVG line charts (no dependency): panels stacked vertically, each with
// axes, "nice" ticks, axis labels with units, a legend, and optional horizontal lines
// (the safety limit).
//
// Layout rules (tests/harness/svg_layout_test.cpp checks them on the SVG): the axes span
// the data (widened to whole ticks); a legend sits in the corner of the plot area that no
// series or line crosses, else outside the plot area on the right (the plot narrows);
// titles wrap to the figure's width. Each panel's <g class="panel"> carries its axis
// ranges (data-x-range, data-y-range), the plot area is <rect class="plot-area">, the
// legend <rect class="legend">, and every series a <polyline class="series"> or dots.
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
  // false: the axis scales to the series alone, and the line is drawn only where it falls
  // inside (the safety limit beside a 0.2 N texture); its legend entry then says so.
  bool sets_range{true};
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

// The pieces of a figure, for figures laid out by hand (engine/harness/planar_figure.cpp).
// The document title's height above the first panel.
inline constexpr double kSvgTitleHeight_px = 40.0;
// A coordinate or length with one decimal ("12.3"); a non-finite value is written as 0.
std::string svg_number(double value);
// Text with &, <, > and " escaped for SVG text and attribute values.
std::string svg_escape(const std::string& text);
// One panel whose top edge is at top_px (its clip path is named after top_px: one panel
// per top).
std::string render_panel_svg(const PlotPanel& panel, double top_px, double width_px, double height_px);
// `text` cut into lines of at most `max_chars` characters at spaces (a word longer than
// a line is cut).
std::vector<std::string> wrap_text(const std::string& text, std::size_t max_chars);
// How many characters of a `font_px` font fit in `width_px` (a conservative average width
// of 0.6 em for Helvetica/Arial).
std::size_t chars_that_fit(double width_px, double font_px);
// The height of a document title wrapped to `width_px`.
double svg_title_height(const std::string& title, int width_px);
// A whole document of the given size: white background, the title, then `body`.
std::string svg_document(const std::string& title, int width_px, double height_px, const std::string& body);

// A whole SVG document.
std::string render_svg(const std::string& title, const std::vector<PlotPanel>& panels,
                       int width_px = 900, int panel_height_px = 260);

}  // namespace hapscene
