// The benchmark's Lua equivalent of a mirrored texture renders the same fields as the
// built-in, on both sides of the mirror.
#include <doctest/doctest.h>

#include "engine/bench/lua_equivalent.hpp"
#include "engine/scene/step.hpp"
#include "tests/support.hpp"

using namespace hapscene;

TEST_CASE("lua equivalent: a mirrored texture gives the built-in's force on both sides of 0") {
  const Scene builtin = test::scene_from(
      R"({"effects": [{"type": "texture", "width": "5 mm", "spacing": "3 mm", "damping": 2, "mirror": true}]})");
  const std::optional<Scene> lua = lua_equivalent(builtin, test::source_path("scripts"));
  REQUIRE(lua);
  TickState a = make_tick_state(builtin);
  TickState b = make_tick_state(*lua);
  int in_field_below_zero = 0;
  for (int i = -500; i <= 500; ++i) {
    const double x_m = i * 1e-4 + 3.7e-6;  // off the decimal edges
    CAPTURE(x_m);
    const EffectInput input{.x_m = x_m, .v_m_per_s = 0.1, .t_s = 0.0, .dt_s = 0.001};
    const double force_N = sum_effects_N(builtin, input, a.scripts);
    CHECK(sum_effects_N(*lua, input, b.scripts) == force_N);
    if (x_m < 0 && force_N != 0.0) ++in_field_below_zero;
  }
  CHECK(in_field_below_zero > 100);
}
