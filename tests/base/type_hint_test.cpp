// The hint after an unknown effect type: a word people use for an effect the format names
// otherwise, a plural or a capital, else the nearest spelling.
#include <doctest/doctest.h>

#include <string_view>
#include <vector>

#include "engine/base/type_hint.hpp"
#include "engine/load/environment.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {
const std::vector<std::string_view> kOneAxis = {"spring", "wall", "damper", "texture", "script"};
const std::vector<std::string_view> kTwoAxes = {"spring", "damper", "texture", "wall", "box", "circle", "polygon", "script"};
}  // namespace

TEST_CASE("type hint: a synonym names the type and how to write it, where the format has that type") {
  CHECK(effect_type_hint("cage", kTwoAxes) == R"( (did you mean "box" with "solid": "outside"?))");
  CHECK(effect_type_hint("Enclosure", kTwoAxes) == R"( (did you mean "box" with "solid": "outside"?))");
  CHECK(effect_type_hint("disk", kTwoAxes) == R"( (did you mean "circle"?))");
  CHECK(effect_type_hint("friction", kOneAxis) == R"( (did you mean "damper" (viscous; a script for Coulomb friction)?))");
  CHECK(effect_type_hint("lua", kOneAxis) == R"( (did you mean "script" with "file": "NAME.lua"?))");
  // 1-D has no box: the nearest spelling instead.
  CHECK(effect_type_hint("cage", kOneAxis) == R"( (did you mean "wall"?))");
}

TEST_CASE("type hint: plurals, capitals and misspellings, and nothing for a word far from every type") {
  CHECK(effect_type_hint("Walls", kOneAxis) == R"( (did you mean "wall"?))");
  CHECK(effect_type_hint("sprnig", kOneAxis) == R"( (did you mean "spring"?))");
  CHECK(effect_type_hint("magnetism", kOneAxis).empty());
  CHECK(effect_type_hint(std::string(10000, 'x'), kTwoAxes).empty());
}

TEST_CASE("type hint: the loaders of both dimensions give it") {
  CHECK(test::load_error(R"({"effects": [{"type": "barrier", "position": 0.01, "stiffness": 100}]})") ==
        R"(test.json: /effects/0/type: unknown effect type "barrier" (did you mean "wall"?))");
  CHECK(test::input_error_of([] {
          load_planar_environment_text(R"({"device": "haplink", "effects": [{"type": "cage", "stiffness": 100}]})",
                                       "test.json");
        }) ==
        R"(test.json: /effects/0/type: unknown 2-D effect type "cage" (did you mean "box" with "solid": "outside"?))");
}
