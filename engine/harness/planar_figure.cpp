#include "engine/harness/planar_figure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "engine/harness/planar_open_loop.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/svg_plot.hpp"
#include "engine/scene/safety.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

constexpr double kPlaneLeft_px = 80.0;
constexpr double kLegend_px = 200.0;        // right of the field: legend and colour bar
constexpr double kPanelTitle_px = 50.0;       // title and the run's line
constexpr double kPlaneBottom_px = 48.0;
constexpr double kMaxFieldHeight_px = 560.0;
constexpr double kMargin = 0.04;            // of the workspace box's size, each side
constexpr int kTimePanelHeight_px = 260;

const char* const kHandleColor = "#1f77b4";
const char* const kProxyColor = "#ff7f0e";
const char* const kShapeColor = "#333333";
const char* const kSolidFill = "#7f7f7f";
const char* const kWorkspaceColor = "#555555";

std::string num(double value) { return svg_number(value); }

std::string format(const char* pattern, double value) {
  char text[128];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

// The arrows' colour for a fraction of the largest force: light blue, orange, dark red.
std::string ramp_color(double fraction) {
  constexpr std::array<std::array<double, 3>, 3> stops{{{120, 170, 220}, {235, 150, 40}, {165, 15, 30}}};
  const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0) * 2.0;
  const int i = std::min(1, static_cast<int>(f));
  const double t = f - i;
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x",
                static_cast<int>(std::lround(stops[i][0] + t * (stops[i + 1][0] - stops[i][0]))),
                static_cast<int>(std::lround(stops[i][1] + t * (stops[i + 1][1] - stops[i][1]))),
                static_cast<int>(std::lround(stops[i][2] + t * (stops[i + 1][2] - stops[i][2]))));
  return text;
}

// Tick values of a step from nice_ticks that lie within [low, high].
std::vector<double> ticks_within(double low, double high, int count) {
  double a = low;
  double b = high;
  std::vector<double> ticks;
  for (const double t : nice_ticks(&a, &b, count)) {
    if (t >= low - 1e-9 * (high - low) && t <= high + 1e-9 * (high - low)) ticks.push_back(t);
  }
  return ticks;
}

std::string tick_text(double value_mm, double step_mm) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step_mm) + 1e-9)));
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, std::abs(value_mm) < step_mm * 1e-6 ? 0.0 : value_mm);
  return text;
}

// "M x y L x y ... Z" of points in the view.
std::string path_of(const PlanarFieldView& view, const std::vector<Vec2>& points_m) {
  std::string d;
  for (std::size_t i = 0; i < points_m.size(); ++i) {
    d += (i == 0 ? "M" : " L") + num(view.px(points_m[i][0])) + " " + num(view.py(points_m[i][1]));
  }
  return d + " Z";
}

std::string points_attribute(const PlanarFieldView& view, const std::vector<Vec2>& points_m) {
  std::string text;
  for (std::size_t i = 0; i < points_m.size(); ++i) {
    text += (i == 0 ? "" : " ") + num(view.px(points_m[i][0])) + "," + num(view.py(points_m[i][1]));
  }
  return text;
}

std::vector<Vec2> view_corners(const PlanarFieldView& view) {
  return {view.min_m, Vec2{{view.max_m[0], view.min_m[1]}}, view.max_m, Vec2{{view.min_m[0], view.max_m[1]}}};
}

// The part of a convex polygon where dot(point - p, normal) > 0 (Sutherland-Hodgman).
std::vector<Vec2> clip_to_half_plane(const std::vector<Vec2>& polygon, const Vec2& point_m, const Vec2& normal) {
  std::vector<Vec2> out;
  const auto depth = [&](const Vec2& p) { return dot(point_m - p, normal); };
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    const double da = depth(a);
    const double db = depth(b);
    if (da > 0.0) out.push_back(a);
    if ((da > 0.0) != (db > 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// The solid parts shaded (a cage: the view outside the shape, by the even-odd rule).
std::string solid_svg(const PlanarFieldView& view, const PlanarShapeGeometry& shape) {
  const std::string style = "\" fill=\"" + std::string(kSolidFill) + "\" fill-opacity=\"0.22\" stroke=\"none\"";
  std::string outline;
  switch (shape.kind) {
    case PlanarShapeKind::wall: {
      const std::vector<Vec2> part = clip_to_half_plane(view_corners(view), shape.point_m, shape.normal);
      if (part.size() < 3) return "";
      return "<path class=\"solid\" d=\"" + path_of(view, part) + style + "/>\n";
    }
    case PlanarShapeKind::circle: {
      const double cy = view.py(shape.center_m[1]);
      const std::string r = num(shape.radius_m * view.scale_px_per_m);
      outline = "M" + num(view.px(shape.center_m[0] + shape.radius_m)) + " " + num(cy) + " A" + r + " " + r +
                " 0 1 0 " + num(view.px(shape.center_m[0] - shape.radius_m)) + " " + num(cy) + " A" + r + " " + r +
                " 0 1 0 " + num(view.px(shape.center_m[0] + shape.radius_m)) + " " + num(cy) + " Z";
      break;
    }
    case PlanarShapeKind::box:
    case PlanarShapeKind::polygon: outline = path_of(view, shape.points_m); break;
  }
  if (shape.solid_inside) return "<path class=\"solid\" d=\"" + outline + style + "/>\n";
  return "<path class=\"solid\" fill-rule=\"evenodd\" d=\"" + path_of(view, view_corners(view)) + " " + outline +
         style + "/>\n";
}

// A wall's line across the view (Liang-Barsky on a long segment along it), or "".
std::string wall_line_svg(const PlanarFieldView& view, const PlanarShapeGeometry& wall) {
  const Vec2 along{{-wall.normal[1], wall.normal[0]}};
  const double reach_m = 4.0 * norm(view.max_m - view.min_m) + norm(wall.point_m - view.min_m);
  const Vec2 a = wall.point_m - reach_m * along;
  const Vec2 d = 2.0 * reach_m * along;
  double t0 = 0.0;
  double t1 = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    const double p[2] = {-d[axis], d[axis]};
    const double q[2] = {a[axis] - view.min_m[axis], view.max_m[axis] - a[axis]};
    for (int k = 0; k < 2; ++k) {
      if (p[k] == 0.0) {
        if (q[k] < 0.0) return "";
        continue;
      }
      const double t = q[k] / p[k];
      if (p[k] < 0.0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
    }
  }
  if (!(t0 < t1)) return "";
  const Vec2 from = a + t0 * d;
  const Vec2 to = a + t1 * d;
  return "<line class=\"shape\" x1=\"" + num(view.px(from[0])) + "\" y1=\"" + num(view.py(from[1])) + "\" x2=\"" +
         num(view.px(to[0])) + "\" y2=\"" + num(view.py(to[1])) + "\" stroke=\"" + kShapeColor +
         "\" stroke-width=\"2\"/>\n";
}

std::string outline_svg(const PlanarFieldView& view, const PlanarShapeGeometry& shape) {
  const std::string style = "\" fill=\"none\" stroke=\"" + std::string(kShapeColor) + "\" stroke-width=\"2\"/>\n";
  switch (shape.kind) {
    case PlanarShapeKind::wall: return wall_line_svg(view, shape);
    case PlanarShapeKind::box: {
      const Vec2& low = shape.points_m[0];
      const Vec2& high = shape.points_m[2];
      return "<rect class=\"shape\" x=\"" + num(view.px(low[0])) + "\" y=\"" + num(view.py(high[1])) +
             "\" width=\"" + num((high[0] - low[0]) * view.scale_px_per_m) + "\" height=\"" +
             num((high[1] - low[1]) * view.scale_px_per_m) + style;
    }
    case PlanarShapeKind::circle:
      return "<circle class=\"shape\" cx=\"" + num(view.px(shape.center_m[0])) + "\" cy=\"" +
             num(view.py(shape.center_m[1])) + "\" r=\"" + num(shape.radius_m * view.scale_px_per_m) + style;
    case PlanarShapeKind::polygon:
      return "<polygon class=\"shape\" points=\"" + points_attribute(view, shape.points_m) + style;
  }
  return "";
}

// One arrow per grid point, centred on it (a dot where the output is zero).
std::string quiver_svg(const PlanarFieldView& view, const PlanarFieldGrid& grid) {
  const double cell_px = std::min(view.width_px / grid.columns, view.height_px / grid.rows) /
                         (1.0 + 2.0 * kMargin);
  std::string out = "<g id=\"quiver\" stroke-width=\"1.3\" stroke-linecap=\"round\" fill=\"none\">\n";
  for (std::size_t i = 0; i < grid.points_m.size(); ++i) {
    const Vec2& p = grid.points_m[i];
    const Vec2& f = grid.output_N[i];
    const double magnitude = norm(f);
    const double cx = view.px(p[0]);
    const double cy = view.py(p[1]);
    if (!(grid.largest_N > 0.0) || !(magnitude > 0.0)) {
      out += "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"1\" fill=\"#bbbbbb\" stroke=\"none\"/>\n";
      continue;
    }
    // Screen direction (y down) and length: the largest force spans 90 % of a cell.
    const double length_px = 0.9 * cell_px * magnitude / grid.largest_N;
    const double ux = f[0] / magnitude;
    const double uy = -f[1] / magnitude;
    const double x0 = cx - 0.5 * length_px * ux;
    const double y0 = cy - 0.5 * length_px * uy;
    const double x1 = cx + 0.5 * length_px * ux;
    const double y1 = cy + 0.5 * length_px * uy;
    const double head_px = std::min(0.35 * length_px, 6.0);
    // The head's two barbs at +/- 25 degrees from the shaft.
    const double c = std::cos(0.436332);
    const double s = std::sin(0.436332);
    const double hx1 = x1 - head_px * (ux * c - uy * s);
    const double hy1 = y1 - head_px * (uy * c + ux * s);
    const double hx2 = x1 - head_px * (ux * c + uy * s);
    const double hy2 = y1 - head_px * (uy * c - ux * s);
    out += "<path d=\"M" + num(x0) + " " + num(y0) + " L" + num(x1) + " " + num(y1) + " M" + num(hx1) + " " +
           num(hy1) + " L" + num(x1) + " " + num(y1) + " L" + num(hx2) + " " + num(hy2) + "\" stroke=\"" +
           ramp_color(magnitude / grid.largest_N) + "\"/>\n";
  }
  return out + "</g>\n";
}

// A path thinned to points at least half a pixel apart (the last one always kept).
std::string path_polyline(const PlanarFieldView& view, const std::vector<PlanarTickRecord>& records, bool proxy,
                          const std::string& id, const std::string& color, double width) {
  std::string points;
  double last_x = INFINITY;
  double last_y = INFINITY;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const Vec2& p = proxy ? records[i].proxy_m : records[i].x_true_m;
    if (!all_finite(p)) continue;
    const double x = view.px(p[0]);
    const double y = view.py(p[1]);
    if (std::hypot(x - last_x, y - last_y) < 0.5 && i + 1 != records.size()) continue;
    points += num(x) + "," + num(y) + " ";
    last_x = x;
    last_y = y;
  }
  return "<polyline id=\"" + id + "\" fill=\"none\" stroke=\"" + color + "\" stroke-width=\"" + num(width) +
         "\" stroke-linejoin=\"round\" points=\"" + points + "\"/>\n";
}

std::string field_panel_svg(const PlanarScene& scene, const PlanarFieldView& view, const PlanarFieldGrid& grid,
                            const std::vector<PlanarTickRecord>& records, const std::string& what,
                            const std::string& proxy_label, double panel_top_px) {
  std::string out = "<g id=\"field\">\n";
  const std::string title = std::string("force field (open loop, v = 0, after the safety rules)") +
                            (records.empty() ? "" : " and one run's paths");
  out += "<text x=\"" + num(view.left_px) + "\" y=\"" + num(panel_top_px + 22) +
         "\" font-size=\"15\" font-weight=\"bold\">" + svg_escape(title) + "</text>\n";
  if (!records.empty()) {
    out += "<text x=\"" + num(view.left_px) + "\" y=\"" + num(panel_top_px + 40) + "\" font-size=\"12\">" +
           svg_escape("run: " + what) + "</text>\n";
  }

  // Grid lines and ticks, in mm.
  const double x0 = view.left_px;
  const double x1 = view.left_px + view.width_px;
  const double y0 = view.top_px;
  const double y1 = view.top_px + view.height_px;
  const std::vector<double> x_ticks = ticks_within(view.min_m[0] * 1e3, view.max_m[0] * 1e3, 8);
  const std::vector<double> y_ticks = ticks_within(view.min_m[1] * 1e3, view.max_m[1] * 1e3, 6);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1.0;
  for (const double t : x_ticks) {
    const double x = view.px(t * 1e-3);
    out += "<line x1=\"" + num(x) + "\" y1=\"" + num(y0) + "\" x2=\"" + num(x) + "\" y2=\"" + num(y1) +
           "\" stroke=\"#eeeeee\"/>\n";
    out += "<text x=\"" + num(x) + "\" y=\"" + num(y1 + 16) + "\" font-size=\"12\" text-anchor=\"middle\">" +
           tick_text(t, x_step) + "</text>\n";
  }
  for (const double t : y_ticks) {
    const double y = view.py(t * 1e-3);
    out += "<line x1=\"" + num(x0) + "\" y1=\"" + num(y) + "\" x2=\"" + num(x1) + "\" y2=\"" + num(y) +
           "\" stroke=\"#eeeeee\"/>\n";
    out += "<text x=\"" + num(x0 - 6) + "\" y=\"" + num(y + 4) + "\" font-size=\"12\" text-anchor=\"end\">" +
           tick_text(t, y_step) + "</text>\n";
  }
  out += "<text x=\"" + num((x0 + x1) / 2) + "\" y=\"" + num(y1 + 36) +
         "\" font-size=\"13\" text-anchor=\"middle\">handle position x (mm)</text>\n";
  out += "<text transform=\"translate(22," + num((y0 + y1) / 2) +
         ") rotate(-90)\" font-size=\"13\" text-anchor=\"middle\">handle position y (mm)</text>\n";

  // The plot area, clipped: solid parts, the arrows, the outlines, the workspace, paths.
  out += "<clipPath id=\"fieldclip\"><rect x=\"" + num(x0) + "\" y=\"" + num(y0) + "\" width=\"" +
         num(view.width_px) + "\" height=\"" + num(view.height_px) + "\"/></clipPath>\n";
  out += "<g clip-path=\"url(#fieldclip)\">\n";
  // The built-in shapes and those the scene's scripts declare (their `shapes`), alike.
  const std::vector<PlanarShapeGeometry> shapes = planar_scenario_shapes(scene);
  for (const PlanarShapeGeometry& shape : shapes) out += solid_svg(view, shape);
  out += quiver_svg(view, grid);
  out += "<g id=\"shapes\">\n";
  for (const PlanarShapeGeometry& shape : shapes) out += outline_svg(view, shape);
  out += "</g>\n<g id=\"workspace\" fill=\"none\" stroke=\"" + std::string(kWorkspaceColor) +
         "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\">\n";
  const Vec2& low = scene.safety.workspace_min_m;
  const Vec2& high = scene.safety.workspace_max_m;
  out += "<rect x=\"" + num(view.px(low[0])) + "\" y=\"" + num(view.py(high[1])) + "\" width=\"" +
         num((high[0] - low[0]) * view.scale_px_per_m) + "\" height=\"" +
         num((high[1] - low[1]) * view.scale_px_per_m) + "\"/>\n";
  if (!scene.safety.workspace_polygon_m.empty()) {
    out += "<polygon points=\"" + points_attribute(view, scene.safety.workspace_polygon_m) + "\"/>\n";
  }
  out += "</g>\n";
  if (!records.empty()) {
    // The proxy under the handle: where the handle is free it follows the measured handle.
    if (!proxy_label.empty()) out += path_polyline(view, records, true, "proxy-path", kProxyColor, 2.4);
    out += path_polyline(view, records, false, "handle-path", kHandleColor, 1.6);
    const Vec2& start = records.front().x_true_m;
    if (all_finite(start)) {
      out += "<circle cx=\"" + num(view.px(start[0])) + "\" cy=\"" + num(view.py(start[1])) +
             "\" r=\"4\" fill=\"white\" stroke=\"" + kHandleColor + "\" stroke-width=\"2\"/>\n";
    }
  }
  out += "</g>\n";
  out += "<rect x=\"" + num(x0) + "\" y=\"" + num(y0) + "\" width=\"" + num(view.width_px) + "\" height=\"" +
         num(view.height_px) + "\" fill=\"none\" stroke=\"#333\"/>\n";

  // Legend and colour bar, right of the plot area.
  const double lx = x1 + 16;
  double ly = y0 + 4;
  const auto entry = [&](const std::string& label, const std::string& color, const std::string& extra) {
    ly += 18;
    out += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly - 4) + "\" x2=\"" + num(lx + 22) + "\" y2=\"" +
           num(ly - 4) + "\" stroke=\"" + color + "\" stroke-width=\"2\"" + extra + "/>\n";
    out += "<text x=\"" + num(lx + 28) + "\" y=\"" + num(ly) + "\" font-size=\"12\">" + svg_escape(label) +
           "</text>\n";
  };
  if (!records.empty()) {
    entry("handle (start: o)", kHandleColor, "");
    if (!proxy_label.empty()) entry(proxy_label, kProxyColor, "");
    if (!proxy_label.empty()) {
      ly += 14;
      out += "<text x=\"" + num(lx + 10) + "\" y=\"" + num(ly) +
             "\" font-size=\"11\">(free: at the measured handle)</text>\n";
    }
  }
  if (!shapes.empty()) entry("shape (solid shaded)", kShapeColor, "");
  entry("workspace", kWorkspaceColor, " stroke-dasharray=\"6 4\"");
  ly += 30;
  out += "<text x=\"" + num(lx) + "\" y=\"" + num(ly) + "\" font-size=\"12\">|F| after safety (N)</text>\n";
  const double bar_top = ly + 8;
  const double bar_height = std::max(60.0, std::min(160.0, y1 - bar_top - 40));
  constexpr int kSteps = 16;
  for (int i = 0; i < kSteps; ++i) {
    const double fraction = 1.0 - (i + 0.5) / kSteps;
    out += "<rect x=\"" + num(lx) + "\" y=\"" + num(bar_top + i * bar_height / kSteps) + "\" width=\"14\" height=\"" +
           num(bar_height / kSteps + 0.5) + "\" fill=\"" + ramp_color(fraction) + "\"/>\n";
  }
  out += "<text x=\"" + num(lx + 20) + "\" y=\"" + num(bar_top + 10) + "\" font-size=\"12\">" +
         format("%.3g", grid.largest_N) + "</text>\n";
  out += "<text x=\"" + num(lx + 20) + "\" y=\"" + num(bar_top + bar_height) + "\" font-size=\"12\">0</text>\n";
  out += "<text x=\"" + num(lx) + "\" y=\"" + num(bar_top + bar_height + 18) +
         "\" font-size=\"11\">arrows to scale: the largest</text>\n";
  out += "<text x=\"" + num(lx) + "\" y=\"" + num(bar_top + bar_height + 32) +
         "\" font-size=\"11\">spans 0.9 grid cell; dot: 0 N</text>\n";
  out += "<text x=\"" + num(lx) + "\" y=\"" + num(bar_top + bar_height + 46) + "\" font-size=\"11\">" +
         svg_escape(format("force limit %g N", scene.safety.max_force_N)) + "</text>\n";
  return out + "</g>\n";
}

// Position and force per axis against time.
std::vector<PlotPanel> planar_time_panels(const PlanarScene& scene, const std::vector<PlanarTickRecord>& records,
                                          const std::string& what, const std::string& proxy_label) {
  PlotPanel position{"position: " + what, "time t (s)", "position (mm)", {}, {}};
  char label[64];
  std::snprintf(label, sizeof label, "safety limit |F| <= %g N", scene.safety.max_force_N);
  PlotPanel force{"force: " + what,
                  "time t (s)",
                  "force (N)",
                  {},
                  {{scene.safety.max_force_N, label}, {-scene.safety.max_force_N, ""}}};
  PlotSeries x{"handle x", "#1f77b4", {}, {}, false};
  PlotSeries y{"handle y", "#2ca02c", {}, {}, false};
  PlotSeries px{proxy_label + " x", "#ff7f0e", {}, {}, true};
  PlotSeries py{proxy_label + " y", "#9467bd", {}, {}, true};
  PlotSeries fx{"commanded x", "#1f77b4", {}, {}, false};
  PlotSeries fy{"commanded y", "#2ca02c", {}, {}, false};
  PlotSeries magnitude{"commanded |F|", "#d62728", {}, {}, false};
  PlotSeries ax{"asked x (before safety)", "#9ecae1", {}, {}, true};
  PlotSeries ay{"asked y (before safety)", "#a1d99b", {}, {}, true};
  bool differs = false;
  const double cut_N = 2.0 * scene.safety.max_force_N;
  for (const PlanarTickRecord& r : records) {
    x.x.push_back(r.t_s), x.y.push_back(r.x_true_m[0] * 1e3);
    y.x.push_back(r.t_s), y.y.push_back(r.x_true_m[1] * 1e3);
    px.x.push_back(r.t_s), px.y.push_back(r.proxy_m[0] * 1e3);
    py.x.push_back(r.t_s), py.y.push_back(r.proxy_m[1] * 1e3);
    fx.x.push_back(r.t_s), fx.y.push_back(r.output_N[0]);
    fy.x.push_back(r.t_s), fy.y.push_back(r.output_N[1]);
    magnitude.x.push_back(r.t_s), magnitude.y.push_back(norm(r.output_N));
    ax.x.push_back(r.t_s), ax.y.push_back(std::clamp(r.requested_N[0], -cut_N, cut_N));
    ay.x.push_back(r.t_s), ay.y.push_back(std::clamp(r.requested_N[1], -cut_N, cut_N));
    differs = differs || !(r.requested_N == r.output_N);
  }
  position.series = {x, y};
  if (!proxy_label.empty()) position.series.push_back(px), position.series.push_back(py);
  force.series = {fx, fy, magnitude};
  if (differs) force.series.push_back(ax), force.series.push_back(ay);
  return {position, force};
}

}  // namespace

PlanarFieldView planar_field_view(const PlanarScene& scene, int figure_width_px, double panel_top_px) {
  const Vec2& low = scene.safety.workspace_min_m;
  const Vec2& high = scene.safety.workspace_max_m;
  const Vec2 margin = (high - low) * kMargin;
  PlanarFieldView view;
  view.min_m = low - margin;
  view.max_m = high + margin;
  const Vec2 span = view.max_m - view.min_m;
  const double max_width_px = std::max(100.0, figure_width_px - kPlaneLeft_px - kLegend_px);
  view.scale_px_per_m = std::min(max_width_px / span[0], kMaxFieldHeight_px / span[1]);
  view.left_px = kPlaneLeft_px;
  view.top_px = panel_top_px + kPanelTitle_px;
  view.width_px = span[0] * view.scale_px_per_m;
  view.height_px = span[1] * view.scale_px_per_m;
  return view;
}

PlanarFieldGrid planar_field_grid(const PlanarScene& scene, int grid) {
  const Vec2& low = scene.safety.workspace_min_m;
  const Vec2& high = scene.safety.workspace_max_m;
  const Vec2 span = high - low;
  PlanarFieldGrid out;
  const bool wide = span[0] >= span[1];
  const int other = std::max(2, static_cast<int>(std::lround(grid * (wide ? span[1] / span[0] : span[0] / span[1]))));
  out.columns = wide ? grid : other;
  out.rows = wide ? other : grid;
  // A scene with scripts: every point as fresh script instances give it at rest, t = 0
  // (the open loop of `probe` and the test specs); built-in effects alone: summed here.
  std::vector<Vec2> points_m;
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.columns; ++c) {
      points_m.push_back(Vec2{{low[0] + (c + 0.5) * span[0] / out.columns, low[1] + (r + 0.5) * span[1] / out.rows}});
    }
  }
  std::vector<Vec2> scripted_N;
  if (scene.script_count > 0) {
    PlanarOpenLoop open_loop(scene);
    scripted_N = open_loop.scan(points_m, Vec2{}).force_N;
    out.faults = open_loop.faults();
  }
  ScriptList no_scripts;
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.columns; ++c) {
      const std::size_t index = static_cast<std::size_t>(r * out.columns + c);
      EffectInputOf<2> input;
      input.x_m = points_m[index];
      input.dt_s = scene.period_s;
      const Vec2 force_N = scripted_N.empty() ? sum_effects_N(scene, input, no_scripts) : scripted_N[index];
      SafetyCounters counters;
      const Vec2 output_N = apply_static_safety(scene.safety, input.x_m, force_N, &counters);
      out.points_m.push_back(input.x_m);
      out.force_N.push_back(force_N);
      out.output_N.push_back(output_N);
      out.largest_N = std::max(out.largest_N, norm(output_N));
    }
  }
  return out;
}

std::string planar_figure_svg(const PlanarScene& scene, const PlanarFigureOptions& options,
                              const std::vector<PlanarTickRecord>& records, const std::string& what,
                              const std::string& proxy_label, ScriptFaultLog* faults) {
  const std::string title = scene.name + " (" + scene.source_path + ") on " + scene.device.name;
  const double field_top_px = svg_title_height(title, options.width_px);
  const PlanarFieldView view = planar_field_view(scene, options.width_px, field_top_px);
  const PlanarFieldGrid grid = planar_field_grid(scene, options.grid);
  if (faults != nullptr) faults->merge(grid.faults);
  std::string body = field_panel_svg(scene, view, grid, records, what, proxy_label, field_top_px);
  double height_px = view.top_px + view.height_px + kPlaneBottom_px;
  if (!records.empty()) {
    for (const PlotPanel& panel : planar_time_panels(scene, records, what, proxy_label)) {
      body += render_panel_svg(panel, height_px, options.width_px, kTimePanelHeight_px);
      height_px += kTimePanelHeight_px;
    }
  }
  return svg_document(title, options.width_px, std::ceil(height_px), body);
}

}  // namespace hapscene
