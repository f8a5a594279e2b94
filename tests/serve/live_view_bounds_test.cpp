// The live view's stiffness ranges in 2-D: the stable stiffness of a linkage varies with
// the pose (docs/reference/validate.md, "Validation in 2-D": on the Haplink the bound falls from about 134 N/m
// near the base, y = 90 mm, to 42 N/m at the far corner), so each shape's stiffness slider
// ends at the smallest per-pose bound on that shape's boundary inside the workspace, and
// GET /api/scene names the pose. A spring acts everywhere: the workspace grid's lowest.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "engine/harness/planar_bound.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/serve/live_view_support.hpp"

namespace hapscene {
namespace {

using nlohmann::json;

// The same 8 mm disc near the Haplink's base (high bound) and near its far edge (low bound),
// a wall across the workspace at y = 150 mm, and a spring; all at 20 N/m, under every bound.
const char* kShapes = R"({
  "name": "bounds",
  "device": "haplink",
  "effects": [
    {"type": "circle", "center": ["-10 mm", "100 mm"], "radius": "8 mm", "stiffness": "20 N/m", "solid": "inside"},
    {"type": "circle", "center": ["-10 mm", "155 mm"], "radius": "8 mm", "stiffness": "20 N/m", "solid": "inside"},
    {"type": "wall", "point": ["0 mm", "150 mm"], "normal": [0, -1], "stiffness": "20 N/m"},
    {"type": "spring", "stiffness": "20 N/m", "center": ["-20 mm", "120 mm"]},
    {"type": "circle", "center": ["-10 mm", "130 mm"], "radius": "8 mm", "stiffness": "20 N/m", "enabled": false}
  ]
}
)";

const json& stiffness_of(const json& scene, std::size_t effect) {
  for (const json& p : scene["parameters"]) {
    if (p["effect"] == effect && p["parameter"] == "stiffness") return p;
  }
  FAIL("no stiffness for effect " << effect);
  static const json none;
  return none;
}

}  // namespace

TEST_SUITE("threaded") {

TEST_CASE("live view: a 2-D shape's stiffness range ends at the lowest per-pose bound on its boundary, and says where") {
  test::ScratchFolder folder("live_bounds");
  const std::string file = folder.write("bounds.json", kShapes).string();
  test::LiveRun<2> run(file, 1.0);
  httplib::Client client = run.client();
  const json scene = json::parse(client.Get(run.with_token("/api/scene"))->body);

  const json& near = stiffness_of(scene, 0);
  const json& far = stiffness_of(scene, 1);
  // Each bound is at a pose on its circle's rim, and is the max of the slider.
  for (const json* p : {&near, &far}) {
    CAPTURE(p->dump());
    CHECK((*p)["min"] == 0.0);
    CHECK((*p)["max"] == (*p)["bound_N_per_m"]);
    CHECK(((*p)["bound"] == "2fc/D" || (*p)["bound"] == "2b/T"));
    CHECK((*p)["range_from"].get<std::string>().find("the lowest on the shape's boundary") != std::string::npos);
  }
  const auto distance_mm = [](const json& at, double cx_mm, double cy_mm) {
    return std::hypot(at[0].get<double>() * 1e3 - cx_mm, at[1].get<double>() * 1e3 - cy_mm);
  };
  CHECK(distance_mm(near["bound_at_m"], -10, 100) == doctest::Approx(8.0).epsilon(0.01));
  CHECK(distance_mm(far["bound_at_m"], -10, 155) == doctest::Approx(8.0).epsilon(0.01));
  // The same disc far from the base gets less than half the range it gets near it
  // (measured: 113 N/m against 49 N/m).
  const double near_N_per_m = near["max"].get<double>();
  const double far_N_per_m = far["max"].get<double>();
  MESSAGE("near the base " << near_N_per_m << " N/m at " << near["bound_at_m"].dump() << ", far " << far_N_per_m
                           << " N/m at " << far["bound_at_m"].dump());
  CHECK(near_N_per_m > 100.0);
  CHECK(far_N_per_m < 60.0);
  // The far disc's bound is at its far side (larger y: farther from the base).
  CHECK(far["bound_at_m"][1].get<double>() > 0.155);

  // The wall: on its line inside the workspace (y = 150 mm).
  const json& wall = stiffness_of(scene, 2);
  CHECK(wall["bound_at_m"][1].get<double>() == doctest::Approx(0.150).epsilon(1e-6));
  CHECK(wall["max"].get<double>() < near_N_per_m);

  // The spring acts everywhere: the workspace grid's lowest bound (validate's).
  const json& spring = stiffness_of(scene, 3);
  const PlanarStiffnessBound grid = planar_stiffness_bound(run.scene);
  CHECK(spring["max"].get<double>() == doctest::Approx(grid.lowest.bound_N_per_m));
  CHECK(spring["range_from"].get<std::string>().find("a spring acts everywhere") != std::string::npos);
  CHECK(spring["max"].get<double>() < far_N_per_m);

  // A disabled shape has no pose: the device-wide range, and no bound named.
  const json& disabled = stiffness_of(scene, 4);
  CHECK(disabled["bound_at_m"] == nullptr);
  CHECK(disabled["max"].get<double>() == doctest::Approx(run.scene.safety.max_force_N / 0.005));

  // A value above the bound stays inside the range (the slider holds it); the bound stays said.
  int status = 0;
  const json taken = run.post_params({{"effect", 1}, {"parameter", "stiffness"}, {"value", 200}}, &status);
  REQUIRE(status == 200);
  const json& moved = stiffness_of(taken, 1);
  CHECK(moved["max"] == 200.0);
  CHECK(moved["bound_N_per_m"].get<double>() == doctest::Approx(far_N_per_m));
}

}  // TEST_SUITE("threaded")

}  // namespace hapscene
