// The SVG writer: nice ticks, decimation that keeps spikes, escaping.
#include <doctest/doctest.h>

#include <algorithm>

#include "engine/harness/svg_plot.hpp"

using namespace hapscene;

TEST_CASE("svg: ticks at 1, 2 or 5 times a power of ten, covering the data") {
  double low = -5.7;
  double high = 4.2;
  const std::vector<double> ticks = nice_ticks(&low, &high, 6);
  CHECK(low == -6.0);
  CHECK(high == 6.0);
  CHECK(ticks.size() == 7);
  CHECK(ticks[1] - ticks[0] == doctest::Approx(2.0));
  double small_low = 0.0;
  double small_high = 0.013;
  const std::vector<double> small = nice_ticks(&small_low, &small_high, 6);
  CHECK(small[1] - small[0] == doctest::Approx(0.005).epsilon(1e-9));  // 0.013 / 6 rounds up to 0.005
  CHECK(small_high == doctest::Approx(0.015));
}

TEST_CASE("svg: decimation keeps the extremes of every bucket") {
  std::vector<double> x;
  std::vector<double> y;
  for (int i = 0; i < 100000; ++i) {
    x.push_back(i);
    y.push_back(i == 51234 ? 9.0 : 0.0);
  }
  std::vector<double> dx;
  std::vector<double> dy;
  decimate_min_max(x, y, 1000, &dx, &dy);
  CHECK(dx.size() <= 1000);
  CHECK(std::find(dy.begin(), dy.end(), 9.0) != dy.end());
}

TEST_CASE("svg: a document with a panel, escaped text and a limit line") {
  PlotPanel panel{"a < b & c", "x (mm)", "force (N)", {{"data", "#000", {0, 1, 2}, {0, 1, 0}, false}},
                  {{6.0, "limit", "#f00"}}};
  const std::string svg = render_svg("title", {panel});
  CHECK(svg.find("a &lt; b &amp; c") != std::string::npos);
  CHECK(svg.find("<polyline") != std::string::npos);
  CHECK(svg.find("stroke-dasharray=\"8 4\"") != std::string::npos);  // the limit line
  CHECK(svg.find(">limit</text>") != std::string::npos);
}
