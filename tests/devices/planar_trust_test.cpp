// The tick's singularity test without a square root: pose_trust answers "trusted" exactly
// where the Jacobian's condition number is within the profile's limit, over the joint
// space of every shipped profile and at matrices made to sit on either side of the limit.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "engine/devices/planar/planar_profile.hpp"
#include "engine/devices/planar/planar_tick.hpp"
#include "tests/devices/planar_support.hpp"

using namespace hapscene;

namespace {

PoseTrust trust_of(const PlanarTickModel& model, const Jacobian2& j) {
  PlanarTickSensor sensor;
  sensor.pose.valid = true;
  sensor.pose.jacobian = j;
  return pose_trust(model, sensor);
}

PoseTrust trust_by_condition_number(const PlanarTickModel& model, const Jacobian2& j) {
  return condition_number(j) <= model.condition_limit ? PoseTrust::trusted : PoseTrust::near_singular;
}

}  // namespace

TEST_CASE("planar trust: the closed form agrees with the condition number over every profile's joint space") {
  for (const std::string& name : test::shipped_planar_profiles()) {
    CAPTURE(name);
    const PlanarProfile profile = load_planar_profile(name, ".");
    const PlanarTickModel model = compile_planar_tick_model(profile);
    int near_singular = 0;
    int trusted = 0;
    for (int i = -180; i <= 180; i += 3) {
      for (int k = -180; k <= 180; k += 3) {
        const Vec2 q{{i * 3.14159265358979 / 180.0, k * 3.14159265358979 / 180.0}};
        const LinkagePose pose = solve_linkage(profile.linkage, q);
        if (!pose.valid) continue;
        const PoseTrust expected = trust_by_condition_number(model, pose.jacobian);
        CHECK(trust_of(model, pose.jacobian) == expected);
        (expected == PoseTrust::trusted ? trusted : near_singular)++;
      }
    }
    MESSAGE(name, ": ", trusted, " trusted, ", near_singular, " near singular");
    CHECK(trusted > 0);
  }
}

TEST_CASE("planar trust: matrices on either side of the limit, singular and non-finite ones") {
  PlanarTickModel model;
  for (const double limit : {1.0, 1.5, 10.0, 37.0, 1e3, 1e6}) {
    CAPTURE(limit);
    model.condition_limit = limit;
    model.condition_bound = limit + 1.0 / limit;
    // diag(s, 1) has condition number s: the limit itself, and a relative 1e-9 either side.
    for (const double s : {limit * (1.0 - 1e-9), limit, limit * (1.0 + 1e-9), 2.0 * limit}) {
      if (s < 1.0) continue;
      CAPTURE(s);
      Jacobian2 j;
      j.m[0][0] = s;
      j.m[1][1] = 1.0;
      CHECK(trust_of(model, j) == trust_by_condition_number(model, j));
      // Rotated and scaled: the same condition number.
      const double c = std::cos(0.7) * 0.03, n = std::sin(0.7) * 0.03;
      Jacobian2 r;
      r.m[0][0] = c * s;
      r.m[0][1] = -n;
      r.m[1][0] = n * s;
      r.m[1][1] = c;
      if (std::fabs(s / limit - 1.0) > 1e-12) CHECK(trust_of(model, r) == trust_by_condition_number(model, r));
    }
    CHECK(trust_of(model, Jacobian2{}) == PoseTrust::near_singular);
    Jacobian2 rank_one;
    rank_one.m[0][0] = 1.0;
    rank_one.m[0][1] = 2.0;
    rank_one.m[1][0] = 2.0;
    rank_one.m[1][1] = 4.0;
    CHECK(trust_of(model, rank_one) == PoseTrust::near_singular);
    Jacobian2 huge;
    huge.m[0][0] = huge.m[1][1] = std::numeric_limits<double>::infinity();
    CHECK(trust_of(model, huge) == PoseTrust::near_singular);
    Jacobian2 nan;
    nan.m[0][0] = std::numeric_limits<double>::quiet_NaN();
    nan.m[1][1] = 1.0;
    CHECK(trust_of(model, nan) == PoseTrust::near_singular);
  }
  PlanarTickSensor invalid;
  CHECK(pose_trust(model, invalid) == PoseTrust::invalid);
}
