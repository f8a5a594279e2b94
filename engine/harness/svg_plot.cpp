#include "engine/harness/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hapscene {
namespace {

constexpr double kLeft_px = 80.0;
constexpr double kRight_px = 30.0;
constexpr double kTop_px = 36.0;      // panel title
constexpr double kBottom_px = 48.0;   // tick labels and axis label

std::string number(double value) { return svg_number(value); }
// A range bound in full precision, for the panel's data attributes.
std::string printf_double(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}
std::string escape(const std::string& text) { return svg_escape(text); }

// A tick label: as few digits as the tick step needs.
std::string tick_label(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, std::abs(value) < step * 1e-6 ? 0.0 : value);
  return text;
}

struct DataRange {
  double low{INFINITY};
  double high{-INFINITY};
  void add(double v) {
    if (!std::isfinite(v)) return;
    low = std::min(low, v);
    high = std::max(high, v);
  }
  void finish() {
    if (!(low <= high)) low = 0.0, high = 1.0;
    if (high - low < 1e-12) {
      const double pad = std::max(std::abs(low) * 0.1, 1e-3);
      low -= pad;
      high += pad;
    }
  }
};

}  // namespace

std::string svg_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", std::isfinite(value) ? value : 0.0);
  return text;
}

std::string svg_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

namespace {

struct Box {
  double x0, y0, x1, y1;
  bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

// Whether the segment a-b meets the box (Liang-Barsky clipping).
bool segment_meets(const Box& box, double ax, double ay, double bx, double by) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = bx - ax, dy = by - ay;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {ax - box.x0, box.x1 - ax, ay - box.y0, box.y1 - ay};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

// The drawn pieces of a series in pixels: runs of finite points (a non-finite value, such
// as the hand's target while it does not grip, breaks the line).
std::vector<std::vector<std::pair<double, double>>> pixel_runs(const std::vector<double>& xs,
                                                               const std::vector<double>& ys, auto px, auto py) {
  std::vector<std::vector<std::pair<double, double>>> runs(1);
  for (std::size_t i = 0; i < xs.size() && i < ys.size(); ++i) {
    if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
      if (!runs.back().empty()) runs.emplace_back();
      continue;
    }
    runs.back().emplace_back(px(xs[i]), py(ys[i]));
  }
  if (runs.back().empty()) runs.pop_back();
  return runs;
}

constexpr double kPanelTitleFont_px = 15.0;
constexpr double kPanelTitleLine_px = 18.0;
constexpr double kDocumentTitleFont_px = 18.0;
constexpr double kDocumentTitleLine_px = 22.0;

}  // namespace

std::size_t chars_that_fit(double width_px, double font_px) {
  return static_cast<std::size_t>(std::max(10.0, std::floor(width_px / (0.6 * font_px))));
}

std::vector<std::string> wrap_text(const std::string& text, std::size_t max_chars) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find(' ', at);
    if (end == std::string::npos) end = text.size();
    std::string word = text.substr(at, end - at);
    at = end + 1;
    while (word.size() > max_chars) {  // a word longer than a line: cut
      if (!line.empty()) lines.push_back(line), line.clear();
      lines.push_back(word.substr(0, max_chars));
      word = word.substr(max_chars);
    }
    if (line.empty()) line = word;
    else if (line.size() + 1 + word.size() <= max_chars) line += " " + word;
    else lines.push_back(line), line = word;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

double svg_title_height(const std::string& title, int width_px) {
  const std::size_t lines = wrap_text(title, chars_that_fit(width_px - kLeft_px - kRight_px, kDocumentTitleFont_px)).size();
  return kSvgTitleHeight_px + kDocumentTitleLine_px * static_cast<double>(lines - 1);
}

std::string render_panel_svg(const PlotPanel& panel, double top_px, double width_px, double height_px) {
  // Data ranges: the series, and the lines that set the range; widened to whole ticks.
  DataRange xr;
  DataRange yr;
  for (const PlotSeries& s : panel.series) {
    for (double v : s.x) xr.add(v);
    for (double v : s.y) yr.add(v);
  }
  for (const PlotLine& line : panel.lines) {
    if (line.sets_range || !(yr.low <= yr.high)) yr.add(line.y);
  }
  xr.finish();
  yr.finish();
  const std::vector<double> x_ticks = nice_ticks(&xr.low, &xr.high, 8);
  const std::vector<double> y_ticks = nice_ticks(&yr.low, &yr.high, 6);

  // The title, wrapped; the plot area below it.
  const std::vector<std::string> title_lines =
      wrap_text(panel.title, chars_that_fit(width_px - kLeft_px - kRight_px, kPanelTitleFont_px));
  const double x0 = kLeft_px;
  double x1 = width_px - kRight_px;
  const double y0 = top_px + kTop_px + kPanelTitleLine_px * static_cast<double>(title_lines.size() - 1);
  const double y1 = top_px + height_px - kBottom_px;
  const auto py = [&](double v) { return y1 - (v - yr.low) / (yr.high - yr.low) * (y1 - y0); };

  // Legend entries: series, then labelled lines (one beyond the axis says so).
  struct Entry {
    std::string label, color;
    bool dashed, dots;
  };
  std::vector<Entry> entries;
  for (const PlotSeries& s : panel.series) entries.push_back({s.label, s.color, s.dashed, s.markers});
  const auto in_range = [&](double y) { return y >= yr.low && y <= yr.high; };
  for (const PlotLine& line : panel.lines) {
    if (line.label.empty()) continue;
    bool shown = in_range(line.y);
    for (const PlotLine& other : panel.lines) shown = shown || (other.color == line.color && in_range(other.y));
    entries.push_back({line.label + (shown ? "" : " (beyond the axis)"), line.color, true, false});
  }
  std::size_t longest = 0;
  for (const Entry& e : entries) longest = std::max(longest, e.label.size());
  const double legend_w = 40.0 + 7.0 * static_cast<double>(longest);
  const double legend_h = 18.0 * static_cast<double>(entries.size()) + 6;

  // Where the legend goes: the first corner of the plot area no drawn line crosses;
  // otherwise outside on the right, the plot narrowed to make room.
  std::vector<std::pair<std::vector<double>, std::vector<double>>> decimated;
  for (const PlotSeries& s : panel.series) {
    std::vector<double> xs, ys;
    decimate_min_max(s.x, s.y, 1500, &xs, &ys);
    decimated.emplace_back(std::move(xs), std::move(ys));
  }
  const auto px_for = [&](double right) {
    return [&, right](double v) { return x0 + (v - xr.low) / (xr.high - xr.low) * (right - x0); };
  };
  const auto crosses = [&](const Box& box, double right) {
    const auto px = px_for(right);
    for (std::size_t k = 0; k < decimated.size(); ++k) {
      for (const auto& run : pixel_runs(decimated[k].first, decimated[k].second, px, py)) {
        const double pad = panel.series[k].markers ? 3.0 : 1.0;  // dot radius, line width
        const Box grown{box.x0 - pad, box.y0 - pad, box.x1 + pad, box.y1 + pad};
        if (run.size() == 1 && grown.contains(run[0].first, run[0].second)) return true;
        for (std::size_t i = 0; i < run.size(); ++i) {
          if (panel.series[k].markers || i + 1 == run.size()) {
            if (grown.contains(run[i].first, run[i].second)) return true;
            continue;
          }
          if (segment_meets(grown, run[i].first, run[i].second, run[i + 1].first, run[i + 1].second)) return true;
        }
      }
    }
    for (const PlotLine& line : panel.lines) {
      if (in_range(line.y) && py(line.y) >= box.y0 - 1 && py(line.y) <= box.y1 + 1) return true;
    }
    return false;
  };
  Box legend{};
  bool placed = entries.empty();
  for (int corner = 0; corner < 4 && !placed; ++corner) {
    const double lx = corner % 2 == 0 ? x1 - legend_w - 8 : x0 + 8;
    const double ly = corner < 2 ? y0 + 8 : y1 - legend_h - 8;
    const Box box{lx, ly, lx + legend_w, ly + legend_h};
    if (box.x0 >= x0 && box.y0 >= y0 && box.y1 <= y1 && !crosses(box, x1)) legend = box, placed = true;
  }
  if (!placed) {
    x1 = width_px - kRight_px - legend_w - 12;
    legend = Box{x1 + 10, y0, x1 + 10 + legend_w, y0 + legend_h};
  }
  const auto px = px_for(x1);

  std::string out = "<g class=\"panel\" data-x-range=\"" + printf_double(xr.low) + " " + printf_double(xr.high) +
                    "\" data-y-range=\"" + printf_double(yr.low) + " " + printf_double(yr.high) + "\">\n";
  for (std::size_t i = 0; i < title_lines.size(); ++i) {
    out += "<text class=\"title\" x=\"" + number(x0) + "\" y=\"" +
           number(top_px + 22 + kPanelTitleLine_px * static_cast<double>(i)) +
           "\" font-size=\"15\" font-weight=\"bold\">" + escape(title_lines[i]) + "</text>\n";
  }

  // Grid and ticks.
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1.0;
  for (double t : x_ticks) {
    out += "<line x1=\"" + number(px(t)) + "\" y1=\"" + number(y0) + "\" x2=\"" + number(px(t)) +
           "\" y2=\"" + number(y1) + "\" stroke=\"#e5e5e5\"/>\n";
    out += "<text x=\"" + number(px(t)) + "\" y=\"" + number(y1 + 16) +
           "\" font-size=\"12\" text-anchor=\"middle\">" + tick_label(t, x_step) + "</text>\n";
  }
  for (double t : y_ticks) {
    out += "<line x1=\"" + number(x0) + "\" y1=\"" + number(py(t)) + "\" x2=\"" + number(x1) +
           "\" y2=\"" + number(py(t)) + "\" stroke=\"#e5e5e5\"/>\n";
    out += "<text x=\"" + number(x0 - 6) + "\" y=\"" + number(py(t) + 4) +
           "\" font-size=\"12\" text-anchor=\"end\">" + tick_label(t, y_step) + "</text>\n";
  }
  // Zero lines, axes box, axis labels.
  if (yr.low < 0.0 && yr.high > 0.0) {
    out += "<line x1=\"" + number(x0) + "\" y1=\"" + number(py(0)) + "\" x2=\"" + number(x1) + "\" y2=\"" +
           number(py(0)) + "\" stroke=\"#999\"/>\n";
  }
  out += "<rect class=\"plot-area\" x=\"" + number(x0) + "\" y=\"" + number(y0) + "\" width=\"" + number(x1 - x0) +
         "\" height=\"" + number(y1 - y0) + "\" fill=\"none\" stroke=\"#333\"/>\n";
  out += "<text x=\"" + number((x0 + x1) / 2) + "\" y=\"" + number(y1 + 36) +
         "\" font-size=\"13\" text-anchor=\"middle\">" + escape(panel.x_label) + "</text>\n";
  out += "<text transform=\"translate(" + number(22) + "," + number((y0 + y1) / 2) +
         ") rotate(-90)\" font-size=\"13\" text-anchor=\"middle\">" + escape(panel.y_label) + "</text>\n";

  // Horizontal lines (safety limits) inside the range, then the series, clipped to the plot area.
  const std::string clip = "clip" + number(top_px).substr(0, number(top_px).find('.'));
  out += "<clipPath id=\"" + clip + "\"><rect x=\"" + number(x0) + "\" y=\"" + number(y0) + "\" width=\"" +
         number(x1 - x0) + "\" height=\"" + number(y1 - y0) + "\"/></clipPath>\n";
  out += "<g clip-path=\"url(#" + clip + ")\">\n";
  for (const PlotLine& line : panel.lines) {
    if (!in_range(line.y)) continue;
    out += "<line class=\"limit\" x1=\"" + number(x0) + "\" y1=\"" + number(py(line.y)) + "\" x2=\"" + number(x1) +
           "\" y2=\"" + number(py(line.y)) + "\" stroke=\"" + line.color +
           "\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"/>\n";
  }
  for (std::size_t k = 0; k < panel.series.size(); ++k) {
    const PlotSeries& s = panel.series[k];
    for (const auto& run : pixel_runs(decimated[k].first, decimated[k].second, px, py)) {
      if (s.markers) {
        for (const auto& [x, y] : run) {
          out += "<circle class=\"series\" cx=\"" + number(x) + "\" cy=\"" + number(y) + "\" r=\"3\" fill=\"" +
                 s.color + "\"/>\n";
        }
        continue;
      }
      out += "<polyline class=\"series\" fill=\"none\" stroke=\"" + s.color + "\" stroke-width=\"1.6\"" +
             (s.dashed ? " stroke-dasharray=\"5 3\"" : "") + " points=\"";
      for (const auto& [x, y] : run) out += number(x) + "," + number(y) + " ";
      out += "\"/>\n";
    }
  }
  out += "</g>\n";

  // The legend where it was placed.
  if (!entries.empty()) {
    out += "<rect class=\"legend\" x=\"" + number(legend.x0) + "\" y=\"" + number(legend.y0) + "\" width=\"" +
           number(legend_w) + "\" height=\"" + number(legend_h) +
           "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#bbb\"/>\n";
  }
  double ly = legend.y0;
  for (const Entry& e : entries) {
    ly += 18;
    if (e.dots) {
      out += "<circle cx=\"" + number(legend.x0 + 18) + "\" cy=\"" + number(ly - 4) + "\" r=\"3\" fill=\"" + e.color +
             "\"/>\n";
    } else {
      out += "<line x1=\"" + number(legend.x0 + 6) + "\" y1=\"" + number(ly - 4) + "\" x2=\"" + number(legend.x0 + 30) +
             "\" y2=\"" + number(ly - 4) + "\" stroke=\"" + e.color + "\" stroke-width=\"2\"" +
             (e.dashed ? " stroke-dasharray=\"5 3\"" : "") + "/>\n";
    }
    out += "<text x=\"" + number(legend.x0 + 36) + "\" y=\"" + number(ly) + "\" font-size=\"12\">" + escape(e.label) +
           "</text>\n";
  }
  out += "</g>\n";
  return out;
}

std::vector<double> nice_ticks(double* low, double* high, int target_count) {
  const double span = *high - *low;
  const double rough = span / std::max(1, target_count);
  const double power = std::pow(10.0, std::floor(std::log10(rough)));
  double step = power;
  for (const double factor : {1.0, 2.0, 5.0, 10.0}) {
    step = factor * power;
    if (step >= rough) break;
  }
  *low = std::floor(*low / step + 1e-9) * step;
  *high = std::ceil(*high / step - 1e-9) * step;
  std::vector<double> ticks;
  const auto count = static_cast<int>(std::llround((*high - *low) / step));
  for (int i = 0; i <= count; ++i) ticks.push_back(*low + i * step);
  return ticks;
}

void decimate_min_max(const std::vector<double>& x, const std::vector<double>& y,
                      std::size_t max_points, std::vector<double>* out_x, std::vector<double>* out_y) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n <= max_points || max_points < 4) {
    out_x->assign(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n));
    out_y->assign(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
    return;
  }
  // Each bucket contributes its extremes in the order they occur.
  const std::size_t buckets = max_points / 2;
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t begin = b * n / buckets;
    const std::size_t end = (b + 1) * n / buckets;
    std::size_t lo = begin;
    std::size_t hi = begin;
    for (std::size_t i = begin; i < end; ++i) {
      if (y[i] < y[lo]) lo = i;
      if (y[i] > y[hi]) hi = i;
    }
    for (const std::size_t i : {std::min(lo, hi), std::max(lo, hi)}) {
      out_x->push_back(x[i]);
      out_y->push_back(y[i]);
    }
  }
}

std::string svg_document(const std::string& title, int width_px, double height_px, const std::string& body) {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width_px) + "\" height=\"" +
         number(height_px) + "\" viewBox=\"0 0 " + std::to_string(width_px) + " " + number(height_px) +
         "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  out += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const std::vector<std::string> lines =
      wrap_text(title, chars_that_fit(width_px - kLeft_px - kRight_px, kDocumentTitleFont_px));
  for (std::size_t i = 0; i < lines.size(); ++i) {
    out += "<text class=\"title\" x=\"" + number(kLeft_px) + "\" y=\"" +
           number(26 + kDocumentTitleLine_px * static_cast<double>(i)) + "\" font-size=\"18\" font-weight=\"bold\">" +
           escape(lines[i]) + "</text>\n";
  }
  out += body;
  out += "</svg>\n";
  return out;
}

std::string render_svg(const std::string& title, const std::vector<PlotPanel>& panels, int width_px,
                       int panel_height_px) {
  const double title_px = svg_title_height(title, width_px);
  const double height_px = title_px + static_cast<double>(panels.size()) * panel_height_px;
  std::string body;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    body += render_panel_svg(panels[i], title_px + static_cast<double>(i) * panel_height_px, width_px,
                             panel_height_px);
  }
  return svg_document(title, width_px, height_px, body);
}

}  // namespace hapscene
