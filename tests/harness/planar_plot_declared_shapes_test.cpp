// The 2-D figure draws the shapes a script declares (its `shapes`) as it draws the
// built-in ones: the scripted twins of the lab's box and circle show the same outline and
// the same shaded solid as their built-in twins (before, a scripted scene's figure drew
// no shape at all), and a script declaring several shapes gets each of them drawn.
#include <doctest/doctest.h>

#include <string>

#include "engine/harness/planar_figure.hpp"
#include "engine/load/environment.hpp"
#include "tests/harness/planar_harness_support.hpp"

using namespace hapscene;

namespace {

// The text from `from` to the next `to` (empty when `from` is missing).
std::string between(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t begin = text.find(from);
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find(to, begin) - begin);
}

// Every line of the figure that draws a shape: its outline and its shaded solid.
std::string shape_lines(const std::string& svg) {
  std::string out;
  std::size_t at = 0;
  while (at < svg.size()) {
    const std::size_t end = svg.find('\n', at);
    const std::string line = svg.substr(at, end - at);
    if (line.find("class=\"shape\"") != std::string::npos || line.find("class=\"solid\"") != std::string::npos) {
      out += line + "\n";
    }
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("planar figure: a script's declared shapes are drawn as its built-in twin's") {
  for (const char* name : {"box_inside", "box_outside", "circle_inside", "circle_outside"}) {
    CAPTURE(name);
    const PlanarScene builtin = test::shipped_planar(std::string("haplink_") + name);
    PlanarScene scripted = test::shipped_planar(std::string("haplink_script_") + name);
    // The same title (it sets where the plot area starts), so the drawings compare as text.
    scripted.name = builtin.name;
    scripted.source_path = builtin.source_path;
    const std::string drawn = shape_lines(planar_figure_svg(scripted, {}, {}, "", ""));
    CHECK(drawn != "");
    CHECK(drawn == shape_lines(planar_figure_svg(builtin, {}, {}, "", "")));
    CHECK(planar_figure_svg(scripted, {}, {}, "", "").find("shape (solid shaded)") != std::string::npos);
  }
}

TEST_CASE("planar figure: every shape of the maze's script is drawn") {
  const std::string svg = planar_figure_svg(test::shipped_planar("haplink_maze"), {}, {}, "", "");
  const std::string group = between(svg, "<g id=\"shapes\"", "</g>");
  CHECK(count(group, "<rect class=\"shape\"") == 9);  // four frame walls and five inner ones
  CHECK(count(svg, "<path class=\"solid\"") == 9);
}

TEST_CASE("planar figure: a script's force counts in the field grid, as its built-in twin's") {
  // Before, the grid summed the built-in effects only: a scripted scene showed no field.
  const PlanarScene builtin = test::shipped_planar("haplink_box_inside");
  const PlanarScene scripted = test::shipped_planar("haplink_script_box_inside");
  const PlanarFieldGrid a = planar_field_grid(builtin, 24);
  const PlanarFieldGrid b = planar_field_grid(scripted, 24);
  REQUIRE(a.output_N.size() == b.output_N.size());
  for (std::size_t i = 0; i < a.output_N.size(); ++i) {
    CHECK(a.output_N[i][0] == b.output_N[i][0]);
    CHECK(a.output_N[i][1] == b.output_N[i][1]);
  }
  CHECK(b.largest_N > 0.0);
  CHECK(planar_field_grid(test::shipped_planar("haplink_maze"), 24).largest_N > 0.0);
}
