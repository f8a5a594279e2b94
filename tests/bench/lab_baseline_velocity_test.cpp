// The hand-written lab baseline's velocity is the 2019 sketch's: 0.9 of the new raw
// difference plus 0.1 of the previous raw difference (not of the previous estimate).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "engine/bench/lab_baseline.hpp"

using namespace hapscene;

TEST_CASE("lab baseline: the damper's velocity averages the new and previous raw differences") {
  // Constants that make xh = raw counts in m, T = 1 s, B = 1, and duty = sqrt(|F|).
  LabBaselineConstants c;
  c.slope_deg_per_count = 1.0;
  c.offset_deg = 0.0;
  c.flip_threshold_counts = 700;
  c.span_counts = 922;
  c.handle_radius_m = 180.0 / std::numbers::pi;
  c.pulley_radius_m = 1.0;
  c.sector_radius_m = 1.0;
  c.motor_constant_N_m = c.handle_radius_m;
  c.period_s = 1.0;
  c.damping_N_s_per_m = 1.0;
  LabBaselineState s;
  lab_damper_tick(c, 100, &s);
  lab_damper_tick(c, 100, &s);
  lab_damper_tick(c, 101, &s);  // dxh = 1: F = -0.9
  CHECK(s.duty == doctest::Approx(std::sqrt(0.9)));
  lab_damper_tick(c, 101, &s);  // dxh = 0: F = -0.1 * 1 (a recursive filter gives -0.09)
  CHECK(s.duty == doctest::Approx(std::sqrt(0.1)));
  lab_damper_tick(c, 101, &s);
  CHECK(s.duty == 0.0);
}
