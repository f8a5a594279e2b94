// The energy 2-D scripts store, for validate's passivity observer
// (engine/harness/planar_script_potential.hpp): the potential of a conservative scripted
// field (bumps) matches its formula, a linear field's is exact, a field with a kink and a
// jump (the scripted box) stays flat off the box, a whirl (vortex) has none, a script
// with state gets its at-rest field's on the coarse grid, and bumps' released potential
// no longer counts as energy created.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "engine/harness/planar_script_potential.hpp"
#include "engine/harness/planar_validate.hpp"
#include "engine/load/environment.hpp"
#include "tests/harness/planar_harness_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;

namespace {

// bumps.lua's U: E (exp(-|p - hill|^2 / 2w^2) - exp(-|p - hollow|^2 / 2w^2)).
double bumps_J(const Vec2& p) {
  const double w = 0.01;
  const double energy_J = 1.0 * w * std::exp(0.5);
  const auto bump = [&](double cx, double cy) {
    const double dx = p[0] - cx, dy = p[1] - cy;
    return std::exp(-(dx * dx + dy * dy) / (2 * w * w));
  };
  return energy_J * (bump(-0.035, 0.127) - bump(0.005, 0.127));
}

}  // namespace

TEST_CASE("script potential: bumps' potential is its formula, between grid nodes too") {
  const PlanarScene scene = test::shipped_planar("haplink_bumps");
  const PlanarScriptPotential potential = planar_script_potential(scene);
  REQUIRE_FALSE(potential.empty());
  CHECK(potential.behaviour.static_field());
  CHECK(potential.step_m == doctest::Approx(1e-3));
  CHECK(potential.rotational_fraction < 1e-4);
  // Differences of U over the workspace, on and off the nodes, against the formula
  // (U's scale is E = 16.5 mJ).
  const Vec2 reference{{-0.0153, 0.1421}};
  double worst_J = 0.0;
  for (double x = -0.0697; x <= 0.04; x += 0.00373) {
    for (double y = 0.0903; y <= 0.165; y += 0.00291) {
      const Vec2 p{{x, y}};
      const double grid_J = potential.at_J(p) - potential.at_J(reference);
      const double exact_J = bumps_J(p) - bumps_J(reference);
      worst_J = std::max(worst_J, std::fabs(grid_J - exact_J));
    }
  }
  MESSAGE("bumps: worst error of a potential difference " << worst_J * 1e3 << " mJ");
  CHECK(worst_J < 2e-6);
}

TEST_CASE("script potential: a linear field's potential is exact, with the built-in effects left out") {
  const test::ScratchFolder folder("planar_script_potential_linear");
  const auto script = folder.write("pull.lua", R"(
params = {}
needs = { velocity = false, time = false }
function force(s) return -20 * (s.x + 0.01), -20 * (s.y - 0.13) end
)");
  // 20 N/m: under the 2 N limit over the whole workspace box. A built-in circle beside it:
  // its force is not the script's and is not counted here.
  const auto env = folder.write("pull.json", R"({"name": "pull", "device": ")" HAPSCENE_SOURCE_DIR
                                             R"(/environments/devices/haplink.json", "effects": [
    {"type": "script", "file": "pull.lua"},
    {"type": "circle", "center": ["-30 mm", "110 mm"], "radius": "8 mm", "stiffness": "200 N/m", "solid": "inside"}]})");
  const PlanarScene scene = load_planar_environment_file(env.string());
  const PlanarScriptPotential potential = planar_script_potential(scene);
  REQUIRE_FALSE(potential.empty());
  CHECK(potential.rotational_fraction < 1e-6);
  const auto exact_J = [](const Vec2& p) {
    return 10.0 * ((p[0] + 0.01) * (p[0] + 0.01) + (p[1] - 0.13) * (p[1] - 0.13));
  };
  const Vec2 a{{-0.0301, 0.1103}};  // inside the circle
  for (const Vec2& b : {Vec2{{0.0123, 0.1456}}, Vec2{{-0.0612, 0.0955}}, Vec2{{-0.01, 0.13}}}) {
    CHECK(potential.at_J(b) - potential.at_J(a) == doctest::Approx(exact_J(b) - exact_J(a)).epsilon(1e-9).scale(1e-12));
  }
}

TEST_CASE("script potential: the scripted box's kinks and jump are integrated, so it is flat off the box") {
  // F = K (nearest point of the outline - p) inside: a kink at the outline and a jump
  // where the push flips side. Off the box U is the same everywhere (within 2 uJ, measured).
  const PlanarScene scene = test::shipped_planar("haplink_script_box_inside");
  const PlanarScriptPotential potential = planar_script_potential(scene);
  REQUIRE_FALSE(potential.empty());
  CHECK(potential.rotational_fraction < 1e-3);
  const double off_J = potential.at_J(Vec2{{-0.055, 0.150}});
  for (const Vec2& p : {Vec2{{0.02, 0.100}}, Vec2{{-0.06, 0.095}}, Vec2{{0.035, 0.16}}, Vec2{{-0.02, 0.14}}}) {
    CHECK(std::fabs(potential.at_J(p) - off_J) < 5e-6);  // half of the least energy judged (0.01 mJ)
  }
  // 5 mm into the left side (not near the middle): K d^2 / 2 = 2.5 mJ.
  CHECK(potential.at_J(Vec2{{-0.035, 0.1225}}) - off_J == doctest::Approx(2.5e-3).epsilon(1e-3));
}

TEST_CASE("script potential: a whirl has none, and a script with state gets its at-rest field's on a coarser grid") {
  const PlanarScriptPotential vortex = planar_script_potential(test::shipped_planar("haplink_vortex"));
  CHECK(vortex.behaviour.static_field());
  CHECK(vortex.rotational_fraction > 0.9);

  const PlanarScene mass_spring = test::shipped_planar("haplink_mass_spring");
  const PlanarScriptPotential puck = planar_script_potential(mass_spring);
  REQUIRE_FALSE(puck.empty());
  CHECK(puck.behaviour.stateful);
  CHECK(puck.step_m > 2e-3);  // about 1000 nodes
  CHECK(puck.columns * puck.rows < 1300);
  // Fresh pucks settle where the springs balance: 25 N/m to (-15, 127) mm.
  const auto exact_J = [](const Vec2& p) {
    return 12.5 * ((p[0] + 0.015) * (p[0] + 0.015) + (p[1] - 0.127) * (p[1] - 0.127));
  };
  const Vec2 a{{-0.015, 0.127}};
  const Vec2 b{{0.0131, 0.1502}};
  CHECK(puck.at_J(b) - puck.at_J(a) == doctest::Approx(exact_J(b) - exact_J(a)).epsilon(1e-6));
  CHECK(describe_script_potential(mass_spring, puck).find("keeps state between calls") != std::string::npos);

  // No scripts: nothing.
  const PlanarScene box = test::shipped_planar("haplink_box_inside");
  CHECK(planar_script_potential(box).empty());
  CHECK(planar_script_potential(box).at_J(Vec2{{0.0, 0.12}}) == 0.0);
  CHECK(describe_script_potential(box, planar_script_potential(box)).empty());
}

TEST_CASE("script potential: bumps' released potential is stored energy, not energy created") {
  const PlanarScene scene = test::shipped_planar("haplink_bumps");
  const HarnessOptions options;
  const PlanarValidateScenario free = build_planar_validate_scenario(PlanarValidateKind::free, scene, options);
  // Without the potential (as before): the hill's slope pushing the handle counts as
  // created, as much as the joints dissipate.
  const PlanarScenarioResult without = run_planar_validate_scenario(scene, free, options);
  CHECK(without.metrics.passivity.created_J > 0.9 * without.metrics.passivity.dissipated_J);
  CHECK_FALSE(without.pass);
  const PlanarScriptPotential potential = planar_script_potential(scene);
  const PlanarScenarioResult with = run_planar_validate_scenario(scene, free, options, &potential);
  CHECK(with.pass);
  CHECK(with.metrics.passivity.created_J < 0.3 * with.metrics.passivity.dissipated_J);
  const CheckResult* passivity = test::check_named(with, "passivity");
  REQUIRE(passivity != nullptr);
  CHECK(passivity->detail.find("; stored energy of the script from its field at rest (1 mm grid; 0.0 % of its work "
                               "rotational, shown as created)") != std::string::npos);
}
