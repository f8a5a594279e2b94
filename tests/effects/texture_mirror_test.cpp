// The texture's "mirror" option against the lab solution's formula, which takes |x|:
// a field where fmod(|x|, w + s) < w, so the fields below 0 mirror those above.
#include <doctest/doctest.h>

#include <cmath>
#include <variant>

#include "engine/effects/texture.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {
// The lab's test, as its solution writes it.
bool lab_in_field(double x_m, double width_m, double spacing_m) {
  return std::fmod(std::fabs(x_m), width_m + spacing_m) < width_m;
}

const Texture& only_texture(const Scene& scene) {
  REQUIRE(scene.effects.size() == 1);
  const auto* texture = std::get_if<Texture>(&scene.effects[0]);
  REQUIRE(texture != nullptr);
  return *texture;
}
}  // namespace

TEST_CASE("texture mirror: the lab formula on both sides of 0, away from the edges") {
  for (const double spacing_m : {0.005, 0.003}) {
    CAPTURE(spacing_m);
    const Scene scene = test::scene_from(R"({"effects": [{"type": "texture", "width": "5 mm", "spacing": )" +
                                         std::to_string(spacing_m) + R"(, "damping": 2, "mirror": true}]})");
    const Texture& texture = only_texture(scene);
    CHECK(texture.mirror);
    int fields_below_zero = 0;
    // Every 0.1 mm from -60 to +60 mm, shifted 3.7 um off the decimal edges.
    for (int i = -600; i <= 600; ++i) {
      const double x_m = i * 1e-4 + 3.7e-6;
      CAPTURE(x_m);
      CHECK(texture.in_field(x_m) == lab_in_field(x_m, 0.005, spacing_m));
      CHECK(texture.in_field(-x_m) == texture.in_field(x_m));  // mirror image
      if (x_m < 0 && texture.in_field(x_m)) ++fields_below_zero;
      EffectInput in;
      in.x_m = x_m;
      in.v_m_per_s = 0.1;
      CHECK(texture.force_N(in) == (lab_in_field(x_m, 0.005, spacing_m) ? -0.2 : 0.0));
    }
    CHECK(fields_below_zero > 100);
  }
}

TEST_CASE("texture mirror: edges as written, the field at 0 is 2 w wide") {
  const Texture texture{.width_m = 0.005, .spacing_m = 0.005, .offset_m = 0.0, .damping_N_s_per_m = 1.0,
                        .period_m = 0.01, .mirror = true};
  CHECK(texture.in_field(0.0));
  CHECK(texture.in_field(0.0049));
  CHECK(texture.in_field(-0.0049));
  CHECK_FALSE(texture.in_field(0.005));
  CHECK_FALSE(texture.in_field(-0.005));
  CHECK(texture.in_field(-0.010));
  CHECK(texture.in_field(-0.0149));
  CHECK_FALSE(texture.in_field(-0.015));  // the lab's fmod says 0.00499999... here: decimal edges are snapped
  CHECK(texture.in_field(-0.020));
  // Without mirror the same positions below 0 fall the other way.
  Texture plain = texture;
  plain.mirror = false;
  CHECK_FALSE(plain.in_field(-0.0049));  // (-4.9 mm) mod 10 mm = 5.1 mm: a gap
  CHECK(plain.in_field(-0.0051));        // 4.9 mm: a field
  CHECK_FALSE(texture.in_field(-0.0051));
}

TEST_CASE("texture mirror: about the offset when one is given") {
  const Texture texture{.width_m = 0.002, .spacing_m = 0.008, .offset_m = 0.001, .damping_N_s_per_m = 1.0,
                        .period_m = 0.01, .mirror = true};
  for (const double d_m : {0.0005, 0.0015, 0.0025, 0.0105, 0.0115, 0.0205}) {
    CAPTURE(d_m);
    CHECK(texture.in_field(0.001 + d_m) == texture.in_field(0.001 - d_m));
    CHECK(texture.in_field(0.001 + d_m) == lab_in_field(d_m, 0.002, 0.008));
  }
}

TEST_CASE("texture mirror: default false keeps today's fields, not a boolean is an error") {
  const Scene plain = test::scene_from(R"({"effects": [{"type": "texture", "width": "5 mm", "damping": 2}]})");
  CHECK_FALSE(only_texture(plain).mirror);
  CHECK(only_texture(plain).in_field(-0.0075));  // (-7.5 mm) mod 10 mm = 2.5 mm: a field
  CHECK_FALSE(only_texture(plain).in_field(-0.0025));
  const Scene off = test::scene_from(R"({"effects": [{"type": "texture", "width": "5 mm", "damping": 2, "mirror": false}]})");
  CHECK_FALSE(only_texture(off).mirror);
  CHECK(test::load_error(R"({"effects": [{"type": "texture", "width": "5 mm", "damping": 2, "mirror": "yes"}]})") ==
        "test.json: /effects/0/mirror: expected a boolean, got string");
}
