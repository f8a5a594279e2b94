// The velocity estimators named after the Hapkit sketches against the sketches' own
// arithmetic, on an irregular sequence of positions (a mislabelled filter gives other
// numbers from the second tick on).
#include <doctest/doctest.h>

#include <vector>

#include "engine/scene/velocity.hpp"

using namespace hapscene;

namespace {
const std::vector<double> kPositions_m = {0.0, 0.0012, 0.0030, 0.0031, 0.0018, -0.0007, -0.0007, 0.0040, 0.0041};
}  // namespace

TEST_CASE("velocity: hapkit2019 computes what the 2019 sketch computes, tick by tick") {
  const double period_s = 0.001;
  VelocityEstimatorConfig config{.kind = VelocityEstimatorKind::hapkit2019};
  VelocityState state;
  // The sketch: dxh = (xh - xh_prev) / T; dxh_filt = 0.9 dxh + 0.1 dxh_prev; dxh_prev = dxh.
  double xh_prev = kPositions_m[0];
  double dxh_prev = 0.0;
  CHECK(estimate_velocity(config, 1.0 / period_s, kPositions_m[0], &state) == 0.0);
  for (std::size_t k = 1; k < kPositions_m.size(); ++k) {
    CAPTURE(k);
    const double dxh = (kPositions_m[k] - xh_prev) / period_s;
    const double sketch = 0.9 * dxh + 0.1 * dxh_prev;
    xh_prev = kPositions_m[k];
    dxh_prev = dxh;
    CHECK(estimate_velocity(config, 1.0 / period_s, kPositions_m[k], &state) == doctest::Approx(sketch).epsilon(1e-12));
  }
}

TEST_CASE("velocity: hapkit2013 computes what the 2013 sketch computes (with the scene's period)") {
  const double period_s = 0.0001;
  VelocityEstimatorConfig config{.kind = VelocityEstimatorKind::hapkit2013};
  VelocityState state;
  // vh = 2 0.95 vh1 - 0.95^2 vh2 + (1 - 0.95)^2 (xh - xh1) / T.
  double vh1 = 0.0;
  double vh2 = 0.0;
  estimate_velocity(config, 1.0 / period_s, kPositions_m[0], &state);
  for (std::size_t k = 1; k < kPositions_m.size(); ++k) {
    CAPTURE(k);
    const double vh = 2 * 0.95 * vh1 - 0.95 * 0.95 * vh2 +
                      0.05 * 0.05 * (kPositions_m[k] - kPositions_m[k - 1]) / period_s;
    vh2 = vh1;
    vh1 = vh;
    CHECK(estimate_velocity(config, 1.0 / period_s, kPositions_m[k], &state) == doctest::Approx(vh).epsilon(1e-12));
  }
}
