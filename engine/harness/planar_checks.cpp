#include "engine/harness/planar_checks.hpp"

#include <cmath>

#include "engine/base/format.hpp"
#include "engine/harness/check_parts.hpp"

namespace hapscene {
namespace {

std::string shape_name(const std::vector<PlanarShapeGeometry>& shapes, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= shapes.size()) return "shape";
  return printf_string("%s %d", planar_shape_kind_name(shapes[static_cast<std::size_t>(index)].kind), index);
}

}  // namespace

std::vector<CheckResult> judge_planar_scenario(const PlanarScene& scene, const ValidateThresholds& t,
                                               const std::vector<PlanarShapeGeometry>& shapes,
                                               const PlanarScenarioMetrics& m) {
  std::vector<CheckResult> checks;

  // Force: its magnitude, time at the limit, how fast the vector changes.
  add_force_checks(scene, t, m, &checks);

  // Energy: created by the rendering against the joints' own viscous loss.
  checks.push_back(passivity_check(m.passivity, t));

  // Oscillation in the watch window.
  if (m.oscillation) {
    const OscillationMetrics& o = *m.oscillation;
    const std::string motion =
        printf_string("from %.2f s: %d half-cycles at %.2f Hz around (%.2f, %.2f) mm along (%.2f, %.2f), initial %.3f mm",
                      o.from_s, o.half_cycles, o.frequency_Hz, m.rest_m[0] * 1e3, m.rest_m[1] * 1e3, m.major_axis[0],
                      m.major_axis[1], o.initial_amplitude_m * 1e3);
    add_oscillation_checks(o, t, motion, &checks);
  }

  // Shapes: how deep into a solid, and whether the rendering let the handle through one.
  if (!shapes.empty()) {
    checks.push_back(check_at_most("penetration", m.max_penetration_m, t.max_penetration_m, "m",
                                   m.max_penetration_shape < 0
                                       ? std::string("never inside a solid")
                                       : "deepest into the " + shape_name(shapes, m.max_penetration_shape) + " " +
                                             where_when(m.max_penetration_x_m, m.max_penetration_t_s)));
    CheckResult pop = check_at_most("pop_through", static_cast<double>(m.pop_throughs),
                                    static_cast<double>(t.max_pop_through), "crossings",
                                    "crossings of a solid not held back by the rendering");
    if (m.pop_throughs > 0) {
      pop.detail += "; first through the " + shape_name(shapes, m.first_pop_shape) + " " +
                    where_when(m.first_pop_x_m, m.first_pop_t_s);
    }
    checks.push_back(pop);
  }

  // Singularity: force asked for where the pose made the safety stage hold it.
  checks.push_back(check_at_most(
      "singularity", static_cast<double>(m.pose_hold_force_ticks), static_cast<double>(t.max_singularity_ticks),
      "ticks",
      printf_string("pose held on %llu ticks (%llu with force asked); largest condition number %.1f of limit %g ",
                    static_cast<unsigned long long>(m.pose_hold_ticks),
                    static_cast<unsigned long long>(m.pose_hold_force_ticks), m.max_condition,
                    scene.device_model.condition_limit) +
          where_when(m.max_condition_x_m, m.max_condition_t_s)));

  // Grit, scripts and timing.
  add_jitter_script_and_timing_checks(scene, t, m, "rms second difference of the commanded force vector", &checks);
  return checks;
}

}  // namespace hapscene
