// Scripts in a scene of any number of axes (engine/lua/state_fields.hpp): s has a position
// and a velocity per axis, force(s) returns one number per axis, and every message that
// lists the fields or counts the results follows from the scene's N. Each case runs for
// every N of HAPSCENE_FOR_EACH_AXES, so a new N is checked without a new test.
#include <string>

#include <nlohmann/json.hpp>

#include "engine/base/axes.hpp"
#include "engine/base/errors.hpp"
#include "engine/lua/script.hpp"
#include "engine/lua/state_fields.hpp"
#include "tests/support.hpp"

namespace hapscene {
namespace {

ScriptProgram program_for_axes(const std::string& source, int axes, bool translate = true) {
  ScriptLimits limits;
  limits.translate_force = translate;
  return compile_script("t.lua", source, nlohmann::json::object(), "env.json", "/effects/0/params", limits, axes);
}

std::string load_error_for_axes(const std::string& source, int axes) {
  try {
    program_for_axes(source, axes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// "return -100 * s.x + 2 * s.v" per axis: the fields named as the scene names them.
std::string spring_damper_source(int axes) {
  std::string source = "function force(s) return ";
  for (int i = 0; i < axes; ++i) {
    source += std::string(i == 0 ? "" : ", ") + "-100 * s." + detail::state_field_name(detail::position_field(i), axes) +
              " + 2 * s." + detail::state_field_name(detail::velocity_field(i), axes);
  }
  return source + " end";
}

template <int N>
void check_spring_damper(bool translate) {
  CAPTURE(N);
  CAPTURE(translate);
  auto script = ScriptInstance::create(program_for_axes(spring_damper_source(N), N, translate));
  script->reset();
  ScriptInputOf<N> input;
  for (int i = 0; i < N; ++i) {
    if constexpr (N == 1) {
      input.x_m = 0.01;
      input.v_m_per_s = 0.5;
    } else {
      input.x_m[i] = 0.01 * (i + 1);
      input.v_m_per_s[i] = 0.5 * (i + 1);
    }
  }
  input.dt_s = 0.001;
  const Axes<N> force = script->force_N(input);
  REQUIRE_FALSE(script->disabled());
  for (int i = 0; i < N; ++i) {
    CHECK(component(force, i) == -100 * component(input.x_m, i) + 2 * component(input.v_m_per_s, i));
  }
  // A straight-line numeric force is translated where the translation hands back N values.
  CHECK(script->force_translated() == (translate && N <= 2));
}

TEST_CASE("scripts: s has a position and a velocity per axis, and force returns one number per axis") {
#define HAPSCENE_CHECK_AXES(N)   \
  check_spring_damper<N>(true);  \
  check_spring_damper<N>(false);
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_CHECK_AXES)
#undef HAPSCENE_CHECK_AXES
}

TEST_CASE("scripts: the fields of s are named from the scene's number of axes") {
  char text[128];
  detail::write_state_field_list(1, text, sizeof text);
  CHECK(std::string(text) == "x, v, t, dt");
  detail::write_state_field_list(2, text, sizeof text);
  CHECK(std::string(text) == "x, y, vx, vy, t, dt");
  detail::write_state_at_rest(2, text, sizeof text);
  CHECK(std::string(text) == "x = 0 m, y = 0 m, vx = 0 m/s, vy = 0 m/s, t = 0 s");
  detail::write_scenes_with_field("y", " and ", text, sizeof text);
  CHECK(std::string(text) == "2-D");
  detail::write_scenes_with_field("v", " and ", text, sizeof text);
  CHECK(std::string(text) == "1-D");
  detail::write_scenes_with_field("dt", " or ", text, sizeof text);
  CHECK(std::string(text) == "1-D or 2-D");
  // A name no scene has is not a field anywhere.
  detail::write_scenes_with_field("w", " and ", text, sizeof text);
  CHECK(std::string(text).empty());
  CHECK(detail::scene_axes_supported(1));
  CHECK(detail::scene_axes_supported(2));
  CHECK_FALSE(detail::scene_axes_supported(0));
  CHECK_FALSE(detail::scene_axes_supported(kMaxAxes + 1));
}

TEST_CASE("scripts: a script written for another number of axes is refused at load, saying why") {
  // Each N's spring in every other N's scene: one of its fields is not in the scene, or
  // it returns the wrong count; the message names the scene's own fields.
  for (const int written_for : detail::kSceneAxes) {
    for (const int scene : detail::kSceneAxes) {
      if (scene == written_for) continue;
      CAPTURE(written_for);
      CAPTURE(scene);
      const std::string error = load_error_for_axes(spring_damper_source(written_for), scene);
      char fields[128];
      detail::write_state_field_list(scene, fields, sizeof fields);
      CHECK(error.find("this is a " + std::to_string(scene) + "-D scene") != std::string::npos);
      CHECK(error.find(std::string("(s has ") + fields + ")") != std::string::npos);
      CHECK(error.find("a " + std::to_string(written_for) + "-D script") != std::string::npos);
    }
  }
  // A scene of an unsupported number of axes runs no scripts.
  CHECK(load_error_for_axes("function force(s) return 0 end", kMaxAxes + 1) ==
        "t.lua: a scene of " + std::to_string(kMaxAxes + 1) + " axes cannot run scripts");
}

TEST_CASE("scripts: in a scene of several axes, a wrong count of results disables the script with a message") {
  for (const int axes : detail::kSceneAxes) {
    if (axes == 1) continue;  // one result is kept in 1-D (scripts: the 1-D cases)
    CAPTURE(axes);
    // N + 1 numbers: the load check's call says how many came back and how many are asked.
    std::string source = "function force(s) return 0";
    for (int i = 0; i < axes; ++i) source += ", 0";
    const std::string error = load_error_for_axes(source + " end", axes);
    CHECK(error.find("force(s) returned " + std::to_string(axes + 1) + " values, expected") != std::string::npos);
    CHECK(error.find("finite numbers fx, fy") != std::string::npos);
  }
}

}  // namespace
}  // namespace hapscene
