// Layout rules of the figures, checked on the SVG itself: each panel's axes span its data
// and are not ten times wider; a legend box meets no drawn line or dot; title lines fit
// the figure's width; the hand's target motion and a run's force against position are
// drawn.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "engine/harness/svg_plot.hpp"
#include "tests/cli/cli_support.hpp"

using namespace hapscene;

namespace {

// The value of attribute `name` in the tag starting at `at`.
std::string attribute(const std::string& svg, std::size_t at, const std::string& name) {
  const std::size_t end = svg.find('>', at);
  const std::size_t found = svg.find(" " + name + "=\"", at);
  if (found == std::string::npos || found > end) return "";
  const std::size_t from = found + name.size() + 3;
  return svg.substr(from, svg.find('"', from) - from);
}

std::vector<double> numbers(std::string text) {
  std::replace(text.begin(), text.end(), ',', ' ');
  std::istringstream in(text);
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

struct Rect {
  double x0, y0, x1, y1;
};

Rect rect_at(const std::string& svg, std::size_t at) {
  const double x = std::stod(attribute(svg, at, "x")), y = std::stod(attribute(svg, at, "y"));
  return {x, y, x + std::stod(attribute(svg, at, "width")), y + std::stod(attribute(svg, at, "height"))};
}

// Every panel of a figure: its text, its legend (if any) and the points of its series.
struct Panel {
  std::string text;
  std::vector<double> x_range, y_range;
};

std::vector<Panel> panels_of(const std::string& svg) {
  std::vector<Panel> panels;
  for (std::size_t at = svg.find("<g class=\"panel\""); at != std::string::npos;
       at = svg.find("<g class=\"panel\"", at + 1)) {
    const std::size_t next = svg.find("<g class=\"panel\"", at + 1);
    panels.push_back({svg.substr(at, next == std::string::npos ? std::string::npos : next - at),
                      numbers(attribute(svg, at, "data-x-range")), numbers(attribute(svg, at, "data-y-range"))});
  }
  return panels;
}

// Checks the rules on every panel of a figure.
void check_layout(const std::string& svg, int width_px) {
  // Title lines fit: at most as many characters as 0.6 em each allows between the margins.
  for (std::size_t at = svg.find("<text class=\"title\""); at != std::string::npos;
       at = svg.find("<text class=\"title\"", at + 1)) {
    const std::size_t from = svg.find('>', at) + 1;
    const std::string line = svg.substr(from, svg.find("</text>", from) - from);
    const double font = std::stod(attribute(svg, at, "font-size"));
    CAPTURE(line);
    CHECK(std::stod(attribute(svg, at, "x")) + static_cast<double>(line.size()) * 0.6 * font <= width_px - 29.0);
  }
  for (const Panel& panel : panels_of(svg)) {
    const std::string& p = panel.text;
    // The legend meets no point of any series (segments: sampled every pixel).
    const std::size_t legend_at = p.find("<rect class=\"legend\"");
    std::vector<std::pair<double, double>> points;
    for (std::size_t at = p.find("<polyline class=\"series\""); at != std::string::npos;
         at = p.find("<polyline class=\"series\"", at + 1)) {
      const std::vector<double> v = numbers(attribute(p, at, "points"));
      for (std::size_t i = 0; i + 1 < v.size(); i += 2) {
        points.emplace_back(v[i], v[i + 1]);
        if (i + 3 < v.size()) {
          const double dx = v[i + 2] - v[i], dy = v[i + 3] - v[i + 1];
          const int steps = static_cast<int>(std::ceil(std::hypot(dx, dy)));
          for (int k = 1; k < steps; ++k) points.emplace_back(v[i] + dx * k / steps, v[i + 1] + dy * k / steps);
        }
      }
    }
    for (std::size_t at = p.find("<circle class=\"series\""); at != std::string::npos;
         at = p.find("<circle class=\"series\"", at + 1)) {
      points.emplace_back(std::stod(attribute(p, at, "cx")), std::stod(attribute(p, at, "cy")));
    }
    if (legend_at != std::string::npos) {
      const Rect legend = rect_at(p, legend_at);
      for (const auto& [x, y] : points) {
        const bool inside = x >= legend.x0 && x <= legend.x1 && y >= legend.y0 && y <= legend.y1;
        CHECK_FALSE(inside);
        if (inside) break;
      }
    }
    // Every point lies inside the plot area (the axes cover the data).
    const Rect area = rect_at(p, p.find("<rect class=\"plot-area\""));
    for (const auto& [x, y] : points) {
      const bool inside = x >= area.x0 - 0.1 && x <= area.x1 + 0.1 && y >= area.y0 - 0.1 && y <= area.y1 + 0.1;
      CHECK(inside);
      if (!inside) break;
    }
  }
}

}  // namespace

TEST_CASE("svg layout: the force axis scales to a small force, the limit beyond it says so") {
  // The texture's forces: +/-0.2 N, with a 6 N limit.
  PlotSeries force{"force", "#000", {}, {}, false};
  for (int i = 0; i <= 200; ++i) {
    force.x.push_back(i * 0.01);
    force.y.push_back(0.2 * std::sin(i * 0.3));
  }
  PlotLine upper{6.0, "safety limit +/-6 N"}, lower{-6.0, ""};
  upper.sets_range = lower.sets_range = false;
  const std::string svg = render_svg("texture", {PlotPanel{"force", "t (s)", "force (N)", {force}, {upper, lower}}});
  const std::vector<Panel> panels = panels_of(svg);
  REQUIRE(panels.size() == 1);
  const std::vector<double>& y = panels[0].y_range;
  REQUIRE(y.size() == 2);
  CHECK(y[0] <= -0.19);
  CHECK(y[1] >= 0.19);
  CHECK(y[1] - y[0] <= 10 * 0.4);
  CHECK(svg.find("class=\"limit\"") == std::string::npos);  // out of range: not drawn
  CHECK(svg.find("safety limit +/-6 N (beyond the axis)") != std::string::npos);
  check_layout(svg, 900);

  // A force near the limit: the limit is drawn.
  force.y.assign(force.y.size(), 5.5);
  const std::string near = render_svg("wall", {PlotPanel{"force", "t (s)", "force (N)", {force}, {upper, lower}}});
  CHECK(near.find("class=\"limit\"") != std::string::npos);
  CHECK(near.find("(beyond the axis)") == std::string::npos);
}

TEST_CASE("svg layout: legends avoid the data, long titles wrap") {
  // Data filling every corner: the legend goes outside the plot area.
  PlotSeries zigzag{"zigzag", "#000", {}, {}, false};
  for (int i = 0; i <= 400; ++i) {
    zigzag.x.push_back(i);
    zigzag.y.push_back(i % 2 == 0 ? -1.0 : 1.0);
  }
  const std::string title(300, 'x');
  const std::string long_title = "a title that goes on " + std::string(40, 'y') + " and on and on about the scene " +
                                 "that is plotted, its device, its scenario and its file name";
  const std::string svg = render_svg(long_title, {PlotPanel{long_title, "x", "y", {zigzag}, {}}});
  check_layout(svg, 900);
  CHECK(std::count(svg.begin(), svg.end(), '\n') > 0);
  // Data in the top right only: the legend takes another corner, inside.
  PlotSeries corner{"rising", "#000", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, {0, 0, 0, 0, 0, 0, 0, 0, 0, 5, 10}, false};
  const std::string inside = render_svg("t", {PlotPanel{"p", "x", "y", {corner}, {}}});
  check_layout(inside, 900);
  const Rect area = rect_at(inside, inside.find("<rect class=\"plot-area\""));
  const Rect legend = rect_at(inside, inside.find("<rect class=\"legend\""));
  CHECK(legend.x0 >= area.x0);
  CHECK(legend.x1 <= area.x1);
  CHECK(wrap_text(title, 80).size() == 4);
}

TEST_CASE("svg layout: plot and run --plot figures keep the rules, with the hand's target and force against position" *
          doctest::test_suite("threaded")) {
  const auto svg_path = std::filesystem::temp_directory_path() / ("hapscene_layout_" + std::to_string(getpid()) + ".svg");
  for (const std::string& command :
       {"plot environments/texture.json --scenario shake --output " + svg_path.string(),
        "plot environments/wall.json --output " + svg_path.string(),
        "run environments/spring.json --sim-time --quiet --hand release --hold 20mm --plot " + svg_path.string()}) {
    CAPTURE(command);
    const test::CliOutcome outcome = test::run_cli(command);
    REQUIRE(outcome.exit_code == 0);
    const std::string svg = test::slurp_file(svg_path);
    check_layout(svg, 900);
    CHECK(svg.find(">hand target</text>") != std::string::npos);
    CHECK(svg.find("force against position: ") != std::string::npos);
  }
  // The texture's forces: the force panels' axes are a fraction of the 6 N limit.
  test::run_cli("plot environments/texture.json --scenario shake --output " + svg_path.string());
  const std::vector<Panel> panels = panels_of(test::slurp_file(svg_path));
  for (const Panel& panel : panels) {
    if (panel.text.find(">force (N)</text>") == std::string::npos) continue;
    CAPTURE(panel.y_range[1]);
    CHECK(panel.y_range[1] - panel.y_range[0] < 6.0);
  }
  std::filesystem::remove(svg_path);
}
