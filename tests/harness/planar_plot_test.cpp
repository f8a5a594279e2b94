// The figure of a 2-DOF scene (engine/harness/planar_figure.hpp): well-formed SVG with
// finite numbers and escaped text, one arrow (or dot) per grid point, the shapes drawn
// where they are, the paths of a deterministic closed-loop scenario, and a trace of
// bounded size whatever the run's length.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "engine/harness/planar_figure.hpp"
#include "engine/harness/planar_scenario.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/planar_trace.hpp"
#include "engine/harness/svg_plot.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/safety.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {

PlanarScene planar_scene(const std::string& effects, const std::string& name = "t") {
  return load_planar_environment_text(R"({"name": ")" + name + R"(", "device": "haplink", "effects": [)" + effects +
                                          "]}",
                                      "env.json");
}

const char* kBox =
    R"({"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "inside"})";
const char* kFourShapes =
    R"({"type": "polygon", "points": [["10 mm", "100 mm"], ["30 mm", "100 mm"], ["20 mm", "120 mm"]], "stiffness": 100, "solid": "inside"},
       {"type": "circle", "center": ["-50 mm", "140 mm"], "radius": "8 mm", "stiffness": 100, "solid": "inside"},
       {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "inside"},
       {"type": "wall", "point": [0, "160 mm"], "normal": [0, -1], "stiffness": 100})";

// A small XML well-formedness check: tags nest and close, attribute values are quoted,
// text and attributes hold no raw '<' and no '&' that does not start an entity.
std::string xml_problem(const std::string& text) {
  std::vector<std::string> open;
  std::size_t i = 0;
  const auto entity_ok = [&](std::size_t at) {
    for (const char* e : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"}) {
      if (text.compare(at, std::char_traits<char>::length(e), e) == 0) return true;
    }
    return false;
  };
  if (text.rfind("<?xml", 0) == 0) i = text.find("?>") + 2;
  while (i < text.size()) {
    if (text[i] == '&' && !entity_ok(i)) return "raw & at " + std::to_string(i);
    if (text[i] != '<') {
      if (text[i] == '>') return "raw > at " + std::to_string(i);
      ++i;
      continue;
    }
    const bool closing = text[i + 1] == '/';
    std::size_t j = i + (closing ? 2 : 1);
    const std::size_t name_start = j;
    while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '-' || text[j] == ':')) ++j;
    const std::string name = text.substr(name_start, j - name_start);
    if (name.empty()) return "tag without a name at " + std::to_string(i);
    // Attributes: name="value" pairs.
    while (j < text.size() && text[j] != '>' && text[j] != '/') {
      if (text[j] == ' ' || text[j] == '\n') {
        ++j;
        continue;
      }
      const std::size_t eq = text.find('=', j);
      if (eq == std::string::npos || text[eq + 1] != '"') return "unquoted attribute at " + std::to_string(j);
      const std::size_t end = text.find('"', eq + 2);
      if (end == std::string::npos) return "unterminated attribute at " + std::to_string(j);
      for (std::size_t k = eq + 2; k < end; ++k) {
        if (text[k] == '<') return "raw < in an attribute at " + std::to_string(k);
        if (text[k] == '&' && !entity_ok(k)) return "raw & in an attribute at " + std::to_string(k);
      }
      j = end + 1;
    }
    if (j >= text.size()) return "unterminated tag " + name;
    if (closing) {
      if (open.empty() || open.back() != name) return "</" + name + "> closes " + (open.empty() ? "nothing" : open.back());
      open.pop_back();
      i = j + 1;
    } else if (text[j] == '/') {
      if (text[j + 1] != '>') return "bad self-closing tag " + name;
      i = j + 2;
    } else {
      open.push_back(name);
      i = j + 1;
    }
  }
  return open.empty() ? "" : "unclosed <" + open.back() + ">";
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string between(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t begin = text.find(from);
  REQUIRE(begin != std::string::npos);
  const std::size_t end = text.find(to, begin);
  REQUIRE(end != std::string::npos);
  return text.substr(begin, end - begin);
}

bool no_non_finite(const std::string& svg) {
  return svg.find("nan") == std::string::npos && svg.find("inf") == std::string::npos;
}

}  // namespace

TEST_CASE("planar figure: the shape list follows the run's proxies") {
  const PlanarScene scene = planar_scene(kFourShapes);
  const std::vector<PlanarShapeGeometry> shapes = planar_shape_list(scene);
  REQUIRE(shapes.size() == scene.bank.proxy_count());
  CHECK(shapes[0].kind == PlanarShapeKind::wall);
  CHECK(shapes[1].kind == PlanarShapeKind::box);
  CHECK(shapes[2].kind == PlanarShapeKind::circle);
  CHECK(shapes[3].kind == PlanarShapeKind::polygon);
  // The nearest boundary: the box's right side from (10, 120) mm; the wall's line from below.
  const Vec2 right = shapes[1].nearest_boundary_m(Vec2{{0.010, 0.120}});
  CHECK(right[0] == doctest::Approx(0.0));
  CHECK(right[1] == doctest::Approx(0.120));
  CHECK(shapes[0].nearest_boundary_m(Vec2{{0.0, 0.150}})[1] == doctest::Approx(0.160));
  CHECK(nearest_shape_index(shapes, Vec2{{-0.050, 0.150}}) == 2);  // the circle, 2 mm away
  CHECK(nearest_shape_index({}, Vec2{}) == -1);
}

TEST_CASE("planar figure: the field grid is the open loop after safety, one point per cell") {
  const PlanarScene scene = planar_scene(kBox);
  const PlanarFieldGrid grid = planar_field_grid(scene, 24);
  // haplink's workspace box: 110 mm x 75 mm.
  CHECK(grid.columns == 24);
  CHECK(grid.rows == 16);
  REQUIRE(grid.points_m.size() == 24u * 16u);
  for (std::size_t i = 0; i < grid.points_m.size(); ++i) {
    const Vec2& p = grid.points_m[i];
    const bool in_box = p[0] > -0.040 && p[0] < 0.0 && p[1] > 0.110 && p[1] < 0.135;
    CHECK((norm(grid.output_N[i]) > 0.0) == in_box);
    CHECK(norm(grid.output_N[i]) <= scene.safety.max_force_N + 1e-12);
  }
  CHECK(grid.largest_N > 0.0);
  CHECK(planar_field_grid(scene, 2).columns == 2);
  CHECK(planar_field_grid(scene, 2).rows == 2);
}

TEST_CASE("planar figure: well-formed SVG with one arrow per grid point and the shapes where they are") {
  const PlanarScene scene = planar_scene(kFourShapes, "four <shapes> & a \\\"wall\\\"");
  PlanarFigureOptions options;
  options.grid = 20;
  const std::string svg = planar_figure_svg(scene, options, {}, "", "");
  CHECK(xml_problem(svg) == "");
  CHECK(no_non_finite(svg));
  CHECK(svg.find("four &lt;shapes&gt; &amp; a &quot;wall&quot;") != std::string::npos);

  // One element per grid point: an arrow where the output is not zero, else a dot.
  const PlanarFieldGrid grid = planar_field_grid(scene, 20);
  std::size_t nonzero = 0;
  for (const Vec2& f : grid.output_N) nonzero += norm(f) > 0.0 ? 1 : 0;
  const std::string quiver = between(svg, "<g id=\"quiver\"", "</g>");
  CHECK(count(quiver, "<path ") == nonzero);
  CHECK(count(quiver, "<path ") + count(quiver, "<circle ") == grid.points_m.size());
  CHECK(nonzero > 0);

  // The outlines at the view's coordinates of the shapes.
  const PlanarFieldView view = planar_field_view(scene, options.width_px, kSvgTitleHeight_px);
  const std::string shapes = between(svg, "<g id=\"shapes\"", "</g>");
  const auto n = [](double v) { return svg_number(v); };
  CHECK(shapes.find("<rect class=\"shape\" x=\"" + n(view.px(-0.040)) + "\" y=\"" + n(view.py(0.135)) +
                    "\" width=\"" + n(0.040 * view.scale_px_per_m) + "\" height=\"" +
                    n(0.025 * view.scale_px_per_m) + "\"") != std::string::npos);
  CHECK(shapes.find("<circle class=\"shape\" cx=\"" + n(view.px(-0.050)) + "\" cy=\"" + n(view.py(0.140)) +
                    "\" r=\"" + n(0.008 * view.scale_px_per_m) + "\"") != std::string::npos);
  CHECK(shapes.find("<polygon class=\"shape\" points=\"" + n(view.px(0.010)) + "," + n(view.py(0.100)) + " " +
                    n(view.px(0.030)) + "," + n(view.py(0.100)) + " " + n(view.px(0.020)) + "," +
                    n(view.py(0.120)) + "\"") != std::string::npos);
  // The wall at y = 160 mm crosses the whole view.
  CHECK(shapes.find("<line class=\"shape\" x1=\"" + n(view.px(view.min_m[0])) + "\" y1=\"" + n(view.py(0.160)) +
                    "\" x2=\"" + n(view.px(view.max_m[0])) + "\" y2=\"" + n(view.py(0.160)) + "\"") !=
        std::string::npos);
  // The workspace box, dashed.
  CHECK(between(svg, "<g id=\"workspace\"", "</g>")
            .find("<rect x=\"" + n(view.px(-0.070)) + "\" y=\"" + n(view.py(0.165)) + "\"") != std::string::npos);
  // One scale on both axes: the box keeps its aspect.
  CHECK(view.width_px / view.height_px == doctest::Approx((view.max_m[0] - view.min_m[0]) / (view.max_m[1] - view.min_m[1])));
}

TEST_CASE("planar figure: a cage shades the view outside its outline") {
  const PlanarScene scene = planar_scene(
      R"({"type": "circle", "center": ["-16 mm", "130 mm"], "radius": "20 mm", "stiffness": 100, "solid": "outside"})");
  const std::string svg = planar_figure_svg(scene, {}, {}, "", "");
  CHECK(xml_problem(svg) == "");
  CHECK(svg.find("<path class=\"solid\" fill-rule=\"evenodd\"") != std::string::npos);
}

TEST_CASE("planar figure: a polygon workspace is drawn, and nothing is rendered outside it") {
  // The Haplink's profile with a triangle for a workspace.
  test::ScratchFolder scratch("planar_figure_polygon_workspace");
  std::ifstream file(test::source_path("environments/devices/haplink.json"));
  std::string profile((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::string box = R"("workspace": {"box": {"min": ["-70 mm", "90 mm"], "max": ["40 mm", "165 mm"]}})";
  REQUIRE(profile.find(box) != std::string::npos);
  profile.replace(profile.find(box), box.size(),
                  R"("workspace": {"polygon": [["-70 mm", "90 mm"], ["40 mm", "165 mm"], ["-70 mm", "165 mm"]]})");
  scratch.write("triangle.json", profile);
  const PlanarScene scene = load_planar_environment_text(
      R"({"device": "triangle.json", "effects": [{"type": "spring", "stiffness": 50, "center": [0, "120 mm"]}]})",
      "env.json", scratch.dir.string());
  REQUIRE(scene.safety.workspace_polygon_m.size() == 3);
  const PlanarFieldGrid grid = planar_field_grid(scene, 12);
  for (std::size_t i = 0; i < grid.points_m.size(); ++i) {
    CHECK((norm(grid.output_N[i]) > 0.0) == within_workspace(scene.safety, grid.points_m[i]));
  }
  const std::string svg = planar_figure_svg(scene, {}, {}, "", "");
  CHECK(xml_problem(svg) == "");
  const PlanarFieldView view = planar_field_view(scene, 900, kSvgTitleHeight_px);
  CHECK(between(svg, "<g id=\"workspace\"", "</g>")
            .find("<polygon points=\"" + svg_number(view.px(-0.070)) + "," + svg_number(view.py(0.090)) + " ") !=
        std::string::npos);
}

TEST_CASE("planar figure: the press scenario's paths, deterministic, the proxy stays out of the box") {
  const PlanarScene scene = planar_scene(kBox, "box");
  HarnessOptions options;
  const PlanarScenario press = build_planar_scenario(PlanarScenarioKind::press, scene, options);
  REQUIRE(press.applicable);
  CHECK(press.proxy_index == 0);
  CHECK(press.description.find("into the box") == 0);
  const PlanarScenarioRun first = run_planar_scenario(scene, press, 1);
  const PlanarScenarioRun second = run_planar_scenario(scene, press, 1);
  REQUIRE(first.records.size() == static_cast<std::size_t>(std::llround(press.duration_s * scene.rate_hz)));
  // The handle goes into the box; the proxy never does, and pushes it back out.
  double deepest_m = 0.0;
  for (const PlanarTickRecord& r : first.records) {
    const Vec2& h = r.x_true_m;
    const Vec2& p = r.proxy_m;
    const double handle_depth = std::min({h[0] + 0.040, -h[0], h[1] - 0.110, 0.135 - h[1]});
    const double proxy_depth = std::min({p[0] + 0.040, -p[0], p[1] - 0.110, 0.135 - p[1]});
    deepest_m = std::max(deepest_m, handle_depth);
    CHECK(proxy_depth <= 1e-9);
  }
  CHECK(deepest_m > 0.002);
  const std::string svg = planar_figure_svg(scene, {}, first.records, "press", "proxy of the box");
  CHECK(svg == planar_figure_svg(scene, {}, second.records, "press", "proxy of the box"));
  CHECK(xml_problem(svg) == "");
  CHECK(no_non_finite(svg));
  CHECK(count(svg, "<polyline id=\"handle-path\"") == 1);
  CHECK(count(svg, "<polyline id=\"proxy-path\"") == 1);
  // The time series per axis: position and force panels with x and y.
  CHECK(svg.find(">handle x</text>") != std::string::npos);
  CHECK(svg.find(">handle y</text>") != std::string::npos);
  CHECK(svg.find(">proxy of the box x</text>") != std::string::npos);
  CHECK(svg.find(">commanded x</text>") != std::string::npos);
  CHECK(svg.find(">commanded y</text>") != std::string::npos);
}

TEST_CASE("planar figure: every scenario runs and ends on its path, press needs a shape") {
  const PlanarScene scene = planar_scene(kBox);
  HarnessOptions options;
  for (const PlanarScenarioKind kind :
       {PlanarScenarioKind::sweep, PlanarScenarioKind::line, PlanarScenarioKind::circle}) {
    const PlanarScenario scenario = build_planar_scenario(kind, scene, options);
    CAPTURE(scenario.name);
    REQUIRE(scenario.applicable);
    CHECK(scenario.duration_s > 1.0);
    CHECK(scenario.duration_s < 20.0);
    const PlanarScenarioRun run = run_planar_scenario(scene, scenario, 1);
    CHECK(!run.records.empty());
    CHECK(run.summary.safety.nonfinite_faults == 0);
  }
  const PlanarScene empty = planar_scene(R"({"type": "damper", "damping": 1})");
  const PlanarScenario press = build_planar_scenario(PlanarScenarioKind::press, empty, options);
  CHECK(!press.applicable);
  CHECK(press.proxy_index == -1);
  const std::string svg = planar_figure_svg(empty, {}, {}, "", "");
  CHECK(xml_problem(svg) == "");
  // No force anywhere: a dot per grid point, no arrow.
  CHECK(count(between(svg, "<g id=\"quiver\"", "</g>"), "<path ") == 0);
}

TEST_CASE("planar trace: bounded memory, a long run keeps each bucket's first tick and its peak") {
  PlanarTrace trace(nullptr, 1'000'000, -1);
  const std::size_t capacity = trace.records().capacity();
  TickStateOf<2> state;
  for (std::uint64_t tick = 0; tick < 1'000'000; ++tick) {
    state.t_s = static_cast<double>(tick) * 1e-3;
    state.x_m = Vec2{{state.t_s, 0.0}};
    state.output_N = tick == 123'457 ? Vec2{{0.0, 9.0}} : Vec2{{0.1, 0.0}};
    trace.on_tick(state);
  }
  trace.on_finish(state);
  CHECK(trace.records().capacity() == capacity);  // never grew
  CHECK(trace.records().size() <= kMaxPlanarTraceRecords);
  CHECK(trace.dropped() == 0);
  CHECK(trace.ticks_per_bucket() == 100);
  CHECK(trace.records().front().t_s == 0.0);
  CHECK(trace.records().back().t_s >= 999.8);
  bool peak_kept = false;
  for (const PlanarTickRecord& r : trace.records()) peak_kept = peak_kept || r.output_N[1] == 9.0;
  CHECK(peak_kept);
  // No shape traced: the proxy is the handle.
  CHECK(trace.records()[5].proxy_m == trace.records()[5].x_m);
}

}  // namespace HAPSCENE_TEST_FILE
