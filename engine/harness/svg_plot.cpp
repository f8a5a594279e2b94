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
std::string escape(const std::string& text) { return svg_escape(text); }

// A tick label: as few digits as the tick step needs.
std::string tick_label(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, std::abs(value) < step * 1e-6 ? 0.0 : value);
  return text;
}

struct Range {
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

std::string render_panel_svg(const PlotPanel& panel, double top_px, double width_px, double height_px) {
  // Data ranges, widened to whole ticks.
  Range xr;
  Range yr;
  for (const PlotSeries& s : panel.series) {
    for (double v : s.x) xr.add(v);
    for (double v : s.y) yr.add(v);
  }
  for (const PlotLine& line : panel.lines) yr.add(line.y);
  xr.finish();
  yr.finish();
  const std::vector<double> x_ticks = nice_ticks(&xr.low, &xr.high, 8);
  const std::vector<double> y_ticks = nice_ticks(&yr.low, &yr.high, 6);
  const double x0 = kLeft_px;
  const double x1 = width_px - kRight_px;
  const double y0 = top_px + kTop_px;
  const double y1 = top_px + height_px - kBottom_px;
  const auto px = [&](double v) { return x0 + (v - xr.low) / (xr.high - xr.low) * (x1 - x0); };
  const auto py = [&](double v) { return y1 - (v - yr.low) / (yr.high - yr.low) * (y1 - y0); };

  std::string out = "<g>\n";
  out += "<text x=\"" + number(x0) + "\" y=\"" + number(top_px + 22) +
         "\" font-size=\"15\" font-weight=\"bold\">" + escape(panel.title) + "</text>\n";

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
  out += "<rect x=\"" + number(x0) + "\" y=\"" + number(y0) + "\" width=\"" + number(x1 - x0) +
         "\" height=\"" + number(y1 - y0) + "\" fill=\"none\" stroke=\"#333\"/>\n";
  out += "<text x=\"" + number((x0 + x1) / 2) + "\" y=\"" + number(y1 + 36) +
         "\" font-size=\"13\" text-anchor=\"middle\">" + escape(panel.x_label) + "</text>\n";
  out += "<text transform=\"translate(" + number(22) + "," + number((y0 + y1) / 2) +
         ") rotate(-90)\" font-size=\"13\" text-anchor=\"middle\">" + escape(panel.y_label) + "</text>\n";

  // Horizontal lines (safety limits), then the series, clipped to the plot area.
  const std::string clip = "clip" + number(top_px).substr(0, number(top_px).find('.'));
  out += "<clipPath id=\"" + clip + "\"><rect x=\"" + number(x0) + "\" y=\"" + number(y0) + "\" width=\"" +
         number(x1 - x0) + "\" height=\"" + number(y1 - y0) + "\"/></clipPath>\n";
  out += "<g clip-path=\"url(#" + clip + ")\">\n";
  for (const PlotLine& line : panel.lines) {
    out += "<line x1=\"" + number(x0) + "\" y1=\"" + number(py(line.y)) + "\" x2=\"" + number(x1) +
           "\" y2=\"" + number(py(line.y)) + "\" stroke=\"" + line.color +
           "\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"/>\n";
  }
  for (const PlotSeries& s : panel.series) {
    std::vector<double> xs;
    std::vector<double> ys;
    decimate_min_max(s.x, s.y, 1500, &xs, &ys);
    if (s.markers) {
      for (std::size_t i = 0; i < xs.size(); ++i) {
        if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
        out += "<circle cx=\"" + number(px(xs[i])) + "\" cy=\"" + number(py(ys[i])) + "\" r=\"3\" fill=\"" +
               s.color + "\"/>\n";
      }
      continue;
    }
    out += "<polyline fill=\"none\" stroke=\"" + s.color + "\" stroke-width=\"1.6\"" +
           (s.dashed ? " stroke-dasharray=\"5 3\"" : "") + " points=\"";
    for (std::size_t i = 0; i < xs.size(); ++i) {
      if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
      out += number(px(xs[i])) + "," + number(py(ys[i])) + " ";
    }
    out += "\"/>\n";
  }
  out += "</g>\n";

  // Legend: series, then labelled lines, in the top right corner.
  std::vector<std::pair<std::string, std::pair<std::string, bool>>> entries;
  for (const PlotSeries& s : panel.series) entries.push_back({s.label, {s.color, s.dashed}});
  for (const PlotLine& line : panel.lines) {
    if (!line.label.empty()) entries.push_back({line.label, {line.color, true}});
  }
  std::size_t longest = 0;
  for (const auto& e : entries) longest = std::max(longest, e.first.size());
  const double legend_w = 40.0 + 7.0 * static_cast<double>(longest);
  const double lx = x1 - legend_w - 8;
  double ly = y0 + 8;
  out += "<rect x=\"" + number(lx) + "\" y=\"" + number(ly) + "\" width=\"" + number(legend_w) +
         "\" height=\"" + number(18.0 * static_cast<double>(entries.size()) + 6) +
         "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#bbb\"/>\n";
  for (const auto& [label, style] : entries) {
    ly += 18;
    out += "<line x1=\"" + number(lx + 6) + "\" y1=\"" + number(ly - 4) + "\" x2=\"" + number(lx + 30) +
           "\" y2=\"" + number(ly - 4) + "\" stroke=\"" + style.first + "\" stroke-width=\"2\"" +
           (style.second ? " stroke-dasharray=\"5 3\"" : "") + "/>\n";
    out += "<text x=\"" + number(lx + 36) + "\" y=\"" + number(ly) + "\" font-size=\"12\">" +
           escape(label) + "</text>\n";
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
  out += "<text x=\"" + number(kLeft_px) + "\" y=\"26\" font-size=\"18\" font-weight=\"bold\">" +
         escape(title) + "</text>\n";
  out += body;
  out += "</svg>\n";
  return out;
}

std::string render_svg(const std::string& title, const std::vector<PlotPanel>& panels, int width_px,
                       int panel_height_px) {
  const double height_px = kSvgTitleHeight_px + static_cast<double>(panels.size()) * panel_height_px;
  std::string body;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    body += render_panel_svg(panels[i], kSvgTitleHeight_px + static_cast<double>(i) * panel_height_px, width_px,
                             panel_height_px);
  }
  return svg_document(title, width_px, height_px, body);
}

}  // namespace hapscene
