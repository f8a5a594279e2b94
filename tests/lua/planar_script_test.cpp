// 2-D scripts (docs/reference/lua.md, "Scripts in 2-D"): force(s) reads s.x, s.y, s.vx, s.vy,
// s.t, s.dt and returns fx, fy. The shipped scripts/planar/ files against their formulas,
// the box and circle twins against the built-ins to the bit, faults, the dimension
// checks at load, planar scenes with script effects, and no allocation per call.
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/units.hpp"
#include "engine/load/environment.hpp"
#include "engine/scene/step.hpp"
#include "tests/lua/script_test_support.hpp"
#include "tests/support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using test::read_script;

// SI value of a unit string, as the params conversion computes it.
double si(const char* text) {
  const QuantityParse q = parse_quantity(text);
  REQUIRE_MESSAGE(q.ok, q.error);
  return q.value_si;
}

// scripts/planar/<name> compiled for a 2-D scene.
ScriptProgram compile_planar(const std::string& name, const nlohmann::json& overrides = nlohmann::json::object()) {
  return compile_script("scripts/planar/" + name, read_script("planar/" + name), overrides, "env.json",
                        "/effects/0/params", {}, 2);
}

std::unique_ptr<ScriptInstance> start(const std::string& name,
                                      const nlohmann::json& overrides = nlohmann::json::object()) {
  auto script = ScriptInstance::create(compile_planar(name, overrides));
  script->reset();
  return script;
}

// An inline source named "t.lua", for a scene of `axes` axes.
ScriptProgram inline_program(const std::string& source, int axes) {
  return compile_script("t.lua", source, nlohmann::json::object(), "env.json", "/effects/0/params", {}, axes);
}

std::string load_error(const std::string& source, int axes) {
  try {
    inline_program(source, axes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

PlanarScriptInput at(double x_m, double y_m, double vx = 0.0, double vy = 0.0, double t_s = 0.0) {
  return PlanarScriptInput{Vec2{{x_m, y_m}}, Vec2{{vx, vy}}, t_s, 0.001};
}

// Bit-equal (so +0 and -0 differ, and a NaN equals only the same NaN).
bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

const std::vector<std::string> kScripts = {"box.lua", "circle.lua", "bumps.lua", "mass_spring.lua", "vortex.lua",
                                           "magnet.lua"};

TEST_CASE("planar scripts: each loads in 2-D, says what it should feel like, and declares params") {
  for (const std::string& name : kScripts) {
    CAPTURE(name);
    const std::string text = read_script("planar/" + name);
    CHECK(text.rfind("-- ", 0) == 0);
    CHECK(text.find("Feels like:") != std::string::npos);
    const ScriptProgram program = compile_planar(name);
    CHECK(program.axes == 2);
    CHECK_FALSE(program.params.empty());
    CHECK_FALSE(program.needs_velocity);
    CHECK_FALSE(program.needs_time);
  }
}

// The probe grid of a twin: every millimetre of the haplink's workspace box, plus each
// coordinate the shape itself uses and its neighbours (edges, corners, the centre).
std::vector<double> grid_axis(double low_m, double high_m, std::vector<double> special_m) {
  std::vector<double> values;
  for (double v = low_m; v <= high_m; v += 0.001) values.push_back(v);
  for (const double s : special_m) {
    values.push_back(s);
    values.push_back(std::nextafter(s, -1.0));
    values.push_back(std::nextafter(s, 1.0));
  }
  return values;
}

void check_twin(const std::string& builtin_file, const std::string& script_file, std::vector<double> xs_special,
                std::vector<double> ys_special) {
  const PlanarScene builtin = load_planar_environment_file(test::source_path(builtin_file));
  const PlanarScene scripted = load_planar_environment_file(test::source_path(script_file));
  REQUIRE(scripted.script_count == 1);
  REQUIRE(builtin.script_count == 0);
  ScriptList none;
  ScriptList scripts = make_script_instances(scripted);
  std::size_t points = 0;
  std::size_t pushing = 0;
  for (const double x : grid_axis(-0.07, 0.04, xs_special)) {
    for (const double y : grid_axis(0.09, 0.165, ys_special)) {
      EffectInputOf<2> input;
      input.x_m = Vec2{{x, y}};
      input.dt_s = builtin.period_s;
      const Vec2 expected = sum_effects_N(builtin, input, none);
      const Vec2 got = sum_effects_N(scripted, input, scripts);
      if (!same_bits(expected[0], got[0]) || !same_bits(expected[1], got[1])) {
        FAIL_CHECK("at (" << x << ", " << y << "): built-in (" << expected[0] << ", " << expected[1]
                          << "), script (" << got[0] << ", " << got[1] << ")");
        return;
      }
      ++points;
      if (expected[0] != 0.0 || expected[1] != 0.0) ++pushing;
    }
  }
  CHECK_FALSE(scripts[0]->disabled());
  CHECK(points > 8000);
  CHECK(pushing > 50);  // the grid reaches into the solid
  MESSAGE(script_file << ": " << points << " points bit-equal, " << pushing << " in the solid");
}

TEST_CASE("planar scripts: box.lua equals the built-in box to the bit in open loop, inside and outside") {
  for (const char* side : {"inside", "outside"}) {
    CAPTURE(side);
    const PlanarScene builtin =
        load_planar_environment_file(test::source_path(std::string("environments/planar/haplink_box_") + side + ".json"));
    const PlanarBox& box = builtin.bank.group<PlanarBox>().at(0);
    const double mid_x = 0.5 * (box.min_m[0] + box.max_m[0]);
    const double mid_y = 0.5 * (box.min_m[1] + box.max_m[1]);
    check_twin(std::string("environments/planar/haplink_box_") + side + ".json",
               std::string("environments/planar/haplink_script_box_") + side + ".json",
               {box.min_m[0], box.max_m[0], mid_x}, {box.min_m[1], box.max_m[1], mid_y});
  }
}

TEST_CASE("planar scripts: circle.lua equals the built-in circle to the bit in open loop, inside and outside") {
  for (const char* side : {"inside", "outside"}) {
    CAPTURE(side);
    const PlanarScene builtin = load_planar_environment_file(
        test::source_path(std::string("environments/planar/haplink_circle_") + side + ".json"));
    const PlanarCircle& circle = builtin.bank.group<PlanarCircle>().at(0);
    const double cx = circle.center_m[0];
    const double cy = circle.center_m[1];
    const double r = circle.radius_m;
    check_twin(std::string("environments/planar/haplink_circle_") + side + ".json",
               std::string("environments/planar/haplink_script_circle_") + side + ".json", {cx - r, cx, cx + r},
               {cy - r, cy, cy + r});
  }
}

TEST_CASE("planar scripts: the twins' defaults are the course's haplink scenes") {
  // Each script alone (no overrides) is the shape of the solid-inside scene.
  for (const char* shape : {"box", "circle"}) {
    CAPTURE(shape);
    const PlanarScene builtin = load_planar_environment_file(
        test::source_path(std::string("environments/planar/haplink_") + shape + "_inside.json"));
    auto script = start(std::string(shape) + ".lua");
    ScriptList none;
    for (double x = -0.06; x <= 0.03; x += 0.0007) {
      for (double y = 0.1; y <= 0.16; y += 0.0007) {
        EffectInputOf<2> input;
        input.x_m = Vec2{{x, y}};
        const Vec2 expected = sum_effects_N(builtin, input, none);
        const Vec2 got = script->force_N(at(x, y));
        REQUIRE(same_bits(expected[0], got[0]));
        REQUIRE(same_bits(expected[1], got[1]));
      }
    }
  }
}

TEST_CASE("planar scripts: bumps.lua is -grad U of its two Gaussians, and conservative") {
  auto script = start("bumps.lua");
  const double w = si("10 mm");
  const double E = si("1 N") * w * std::exp(0.5);
  const double hx = si("-35 mm"), hy = si("127 mm"), vx = si("5 mm"), vy = si("127 mm");
  const auto U = [&](double x, double y) {
    const double a = (x - hx) * (x - hx) + (y - hy) * (y - hy);
    const double b = (x - vx) * (x - vx) + (y - vy) * (y - vy);
    return E * (std::exp(-a / (2 * w * w)) - std::exp(-b / (2 * w * w)));
  };
  const double h = 1e-7;
  for (double x = -0.07; x <= 0.04; x += 0.0013) {
    for (double y = 0.09; y <= 0.165; y += 0.0017) {
      const Vec2 f = script->force_N(at(x, y));
      const double gx = (U(x + h, y) - U(x - h, y)) / (2 * h);
      const double gy = (U(x, y + h) - U(x, y - h)) / (2 * h);
      REQUIRE(f[0] == doctest::Approx(-gx).epsilon(1e-6).scale(1.0));
      REQUIRE(f[1] == doctest::Approx(-gy).epsilon(1e-6).scale(1.0));
    }
  }
  // The steepest slope of the hill pushes with peak_force, away from its centre.
  const Vec2 slope = script->force_N(at(hx - w, hy));
  CHECK(slope[0] == doctest::Approx(-1.0).epsilon(1e-3));
  // Work round a closed loop through both is zero (trapezoid rule over 20 000 steps).
  double work_J = 0.0;
  const int steps = 20000;
  const auto point = [&](int i) {
    const double phi = 2 * std::numbers::pi * i / steps;
    return std::pair{-0.015 + 0.03 * std::cos(phi), 0.127 + 0.012 * std::sin(phi)};
  };
  for (int i = 0; i < steps; ++i) {
    const auto [x0, y0] = point(i);
    const auto [x1, y1] = point(i + 1);
    const Vec2 f0 = script->force_N(at(x0, y0));
    const Vec2 f1 = script->force_N(at(x1, y1));
    work_J += 0.5 * ((f0[0] + f1[0]) * (x1 - x0) + (f0[1] + f1[1]) * (y1 - y0));
  }
  CHECK(std::abs(work_J) < 1e-9);
}

TEST_CASE("planar scripts: mass_spring.lua integrates the puck as its header says") {
  auto script = start("mass_spring.lua");
  const double m = 0.2, k = 100, kc = 300, b = 0.5, ax = si("-15 mm"), ay = si("127 mm");
  const double dt = 0.001;
  const double max_step = 0.1 / std::sqrt((k + kc) / m);
  const int steps = static_cast<int>(std::ceil(dt / max_step));
  const double h = dt / steps;
  double qx = 0, qy = 0, wx = 0, wy = 0;
  for (int i = 0; i < 2000; ++i) {
    const double t = i * dt;
    const double x = ax + 0.02 * std::sin(2 * std::numbers::pi * 3 * t);
    const double y = ay + 0.01 * std::cos(2 * std::numbers::pi * 2 * t);
    if (i == 0) {
      qx = (kc * x + k * ax) / (kc + k);
      qy = (kc * y + k * ay) / (kc + k);
    }
    for (int j = 0; j < steps; ++j) {
      const double fx = (kc * (x - qx) - k * (qx - ax) - b * wx) / m;
      const double fy = (kc * (y - qy) - k * (qy - ay) - b * wy) / m;
      wx = wx + fx * h;
      wy = wy + fy * h;
      qx = qx + wx * h;
      qy = qy + wy * h;
    }
    const Vec2 f = script->force_N(PlanarScriptInput{Vec2{{x, y}}, Vec2{}, t, dt});
    REQUIRE(f[0] == doctest::Approx(-kc * (x - qx)).epsilon(1e-12).scale(1.0));
    REQUIRE(f[1] == doctest::Approx(-kc * (y - qy)).epsilon(1e-12).scale(1.0));
  }
  // Held still at the first call, the puck starts at rest: the series spring's force.
  auto fresh = start("mass_spring.lua");
  const Vec2 first = fresh->force_N(at(ax + 0.01, ay));
  CHECK(first[0] == doctest::Approx(-0.01 * kc * k / (kc + k)).epsilon(1e-3));
  CHECK(std::abs(first[1]) < 1e-12);
  // reset() starts the puck over.
  fresh->reset();
  const Vec2 again = fresh->force_N(at(ax + 0.01, ay));
  CHECK(same_bits(again[0], first[0]));
}

TEST_CASE("planar scripts: vortex.lua pushes round its centre, Rankine profile") {
  auto script = start("vortex.lua");
  const double cx = si("-15 mm"), cy = si("127 mm"), R = 0.01, F0 = 0.8;
  for (double x = -0.07; x <= 0.04; x += 0.0011) {
    for (double y = 0.09; y <= 0.165; y += 0.0013) {
      const double dx = x - cx, dy = y - cy;
      const double r2 = dx * dx + dy * dy;
      const double gain = r2 <= R * R ? F0 / R : F0 * R / r2;
      const Vec2 f = script->force_N(at(x, y));
      REQUIRE(same_bits(f[0], -gain * dy));
      REQUIRE(same_bits(f[1], gain * dx));
      // Tangential: no push towards or away from the centre.
      REQUIRE(std::abs(f[0] * dx + f[1] * dy) < 1e-15);
    }
  }
  // Peak F0 on the core's rim, anticlockwise.
  const Vec2 rim = script->force_N(at(cx + R, cy));
  CHECK(rim[1] == doctest::Approx(F0));
  CHECK(rim[0] == 0.0);
}

TEST_CASE("planar scripts: magnet.lua pulls towards its point as the 1-D magnet does along a line") {
  auto script = start("magnet.lua");
  const double mx = si("-15 mm"), my = si("127 mm"), Fmax = 2, ds = 0.003, R = 0.025;
  const double edge = (ds / R) * (ds / R);
  for (double x = -0.07; x <= 0.04; x += 0.0009) {
    for (double y = 0.09; y <= 0.165; y += 0.0011) {
      const double dx = x - mx, dy = y - my;
      const double r = std::sqrt(dx * dx + dy * dy);
      double magnitude = 0.0;
      if (r <= ds) {
        magnitude = Fmax * r / ds;
      } else if (r < R) {
        magnitude = Fmax / (1 - edge) * ((ds / r) * (ds / r) - edge);
      }
      const Vec2 f = script->force_N(at(x, y));
      const double expected_x = r > 0 ? -magnitude * dx / r : 0.0;
      const double expected_y = r > 0 ? -magnitude * dy / r : 0.0;
      REQUIRE(f[0] == doctest::Approx(expected_x).epsilon(1e-12).scale(1.0));
      REQUIRE(f[1] == doctest::Approx(expected_y).epsilon(1e-12).scale(1.0));
    }
  }
  const Vec2 snap = script->force_N(at(mx + ds, my));
  CHECK(snap[0] == doctest::Approx(-Fmax));
  CHECK(std::abs(script->force_N(at(mx, my + R))[1]) < 1e-12);
}

TEST_CASE("planar scripts: s has x, y, vx, vy, t, dt, read-only, needs hides what is not declared") {
  auto script = ScriptInstance::create(inline_program(
      "function force(s) return s.x + 10 * s.vx + 100 * s.t + 1000 * s.dt, s.y + 10 * s.vy end", 2));
  const Vec2 f = script->force_N(PlanarScriptInput{Vec2{{1, 2}}, Vec2{{3, 4}}, 5, 0.5});
  CHECK(f[0] == 1 + 30 + 500 + 500);
  CHECK(f[1] == 2 + 40);
  CHECK(load_error("needs = { velocity = false } function force(s) return s.vy, 0 end", 2)
            .find("s.vy is not available: the script declares needs.velocity = false") != std::string::npos);
  CHECK(load_error("function force(s) s.y = 1 return 0, 0 end", 2).find("s is read-only") != std::string::npos);
  CHECK(load_error("function force(s) return s.position, 0 end", 2).find("(s has x, y, vx, vy, t, dt)") !=
        std::string::npos);
}

TEST_CASE("planar scripts: a bad return disables the script with one message, 0 N from then on") {
  struct Case {
    const char* returns;  // what force returns at x > 1 cm
    const char* message;
  };
  const Case cases[] = {
      {"error('boom')", "t.lua:1: boom"},
      {"-1", "t.lua:1: force(s) returned one number, expected two, fx, fy (N): this is a 2-D scene"},
      {"1, 2, 3", "t.lua:1: force(s) returned 3 values, expected two finite numbers fx, fy (N)"},
      {"", "t.lua:1: force(s) returned 0 values, expected two finite numbers fx, fy (N)"},
      {"0/0, 1", "t.lua:1: force(s) returned nan, 1, expected two finite numbers fx, fy (N)"},
      {"1, math.huge", "t.lua:1: force(s) returned 1, inf, expected two finite numbers fx, fy (N)"},
      {"1, nil", "t.lua:1: force(s) returned a number and a nil, expected two finite numbers fx, fy (N)"},
      {"'1', 2", "t.lua:1: force(s) returned a string and a number, expected two finite numbers fx, fy (N)"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.returns);
    auto script = ScriptInstance::create(inline_program(
        std::string("function force(s) if s.x > 0.01 then return ") + c.returns + " end return 0.5, -0.5 end", 2));
    script->reset();
    const Vec2 ok = script->force_N(at(0.0, 0.1));
    CHECK(ok[0] == 0.5);
    CHECK(ok[1] == -0.5);
    const Vec2 bad = script->force_N(at(0.02, 0.1, 0, 0, 0.25));
    CHECK(bad[0] == 0.0);
    CHECK(bad[1] == 0.0);
    CHECK(script->disabled());
    CHECK(script->fault_count() == 1);
    CHECK(script->fault_time_s() == 0.25);
    CHECK(std::string(script->fault_message()).find(c.message) == 0);
    const Vec2 after = script->force_N(at(0.0, 0.1));
    CHECK(after[0] == 0.0);
    CHECK(after[1] == 0.0);
    CHECK(script->skipped_calls() == 1);
    CHECK(script->fault_count() == 1);
  }
  // A limit overrun is a fault of its own kind, as in 1-D.
  auto runaway = ScriptInstance::create(
      inline_program("function force(s) if s.x > 0.01 then while true do end end return 0, 0 end", 2));
  runaway->force_N(at(0.02, 0.1));
  CHECK(runaway->fault() == ScriptFault::instruction_budget);
}

TEST_CASE("planar scripts: a script of the other dimension is a load error that says so") {
  // A 1-D script in a 2-D scene: one number, or s.v.
  const std::string one = load_error("function force(s) return -100 * s.x end", 2);
  CHECK(one.find("t.lua:1: force(s) returned one number, expected two, fx, fy (N): this is a 2-D scene, and a 1-D "
                 "script returns one") == 0);
  CHECK(one.find("(while checking force(s) at x = 0 m, y = 0 m") != std::string::npos);
  const std::string v = load_error("function force(s) return -s.v end", 2);
  CHECK(v.find("s.v is only in 1-D scenes, and this is a 2-D scene") != std::string::npos);
  // A 2-D script in a 1-D scene: s.y, s.vx, or two results.
  const std::string y = load_error("function force(s) return -s.x, -s.y end", 1);
  CHECK(y.find("s.y is only in 2-D scenes, and this is a 1-D scene (s has x, v, t, dt)") != std::string::npos);
  CHECK(load_error("function force(s) return -s.vx, 0 end", 1).find("s.vx is only in 2-D scenes") !=
        std::string::npos);
  const std::string two = load_error("function force(s) return 1, 2 end", 1);
  CHECK(two.find("t.lua:1: force(s) returned 2 values, expected one number (N): this is a 1-D scene, and a 2-D "
                 "script returns two") == 0);
  // Every shipped 2-D script is refused by a 1-D scene, every shipped 1-D one by a 2-D scene.
  for (const std::string& name : kScripts) {
    CAPTURE(name);
    CHECK_THROWS_WITH_AS(compile_script(name, read_script("planar/" + name), nlohmann::json::object(), "", "", {}, 1),
                         doctest::Contains("only in 2-D scenes"), InputError);
  }
  for (const char* name : {"spring.lua", "texture.lua", "bumps.lua", "detents.lua", "friction.lua", "wall.lua",
                           "mass_spring.lua", "pong.lua", "magnet.lua", "grating.lua", "vibration.lua"}) {
    CAPTURE(name);
    CHECK_THROWS_AS(compile_script(name, read_script(name), nlohmann::json::object(), "", "", {}, 2), InputError);
    // And they still load in 1-D.
    CHECK_NOTHROW(compile_script(name, read_script(name), nlohmann::json::object(), "", "", {}, 1));
  }
}

TEST_CASE("planar scripts: the environment loader names the place of a dimension mismatch") {
  const auto error_of = [](auto load) -> std::string {
    try {
      load();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string planar_with_1d = error_of([] {
    load_planar_environment_text(R"({"device": "haplink", "effects": [
      {"type": "box", "min": ["-40 mm", "110 mm"], "max": ["0 mm", "135 mm"], "stiffness": 200, "solid": "inside"},
      {"type": "script", "file": "scripts/spring.lua"}]})",
                                 "env.json", test::source_path(""));
  });
  CHECK(planar_with_1d.find("env.json: /effects/1/file: ") == 0);
  CHECK(planar_with_1d.find("scripts/spring.lua:") != std::string::npos);
  CHECK(planar_with_1d.find("this is a 2-D scene, and a 1-D script returns one") != std::string::npos);
  const std::string inline_1d = error_of([] {
    load_planar_environment_text(R"({"device": "haplink", "effects": [
      {"type": "script", "source": "function force(s) return 1 end"}]})",
                                 "env.json");
  });
  CHECK(inline_1d.find("env.json#/effects/0/source:1: force(s) returned one number") == 0);
  const std::string hapkit_with_2d = error_of([] {
    load_environment_text(R"({"effects": [{"type": "script", "file": "scripts/planar/box.lua"}]})", "env.json",
                          test::source_path(""));
  });
  CHECK(hapkit_with_2d.find("env.json: /effects/0/file: ") == 0);
  CHECK(hapkit_with_2d.find("scripts/planar/box.lua:") != std::string::npos);
  CHECK(hapkit_with_2d.find("s.y is only in 2-D scenes, and this is a 1-D scene") != std::string::npos);
}

TEST_CASE("planar scripts: a planar scene adds script effects after its built-ins, with their needs") {
  const PlanarScene scene = load_planar_environment_text(R"({"device": "haplink", "effects": [
      {"type": "spring", "stiffness": "100 N/m", "center": ["-10 mm", "130 mm"]},
      {"type": "script", "source": "needs = {velocity = false, time = false} function force(s) return 0.25, -0.5 end"},
      {"type": "script", "enabled": false, "source": "syntax error here"},
      {"type": "script", "source": "params = {k = '2 N*s/m'} local k = params.k function force(s) return -k * s.vx, -k * s.vy end",
       "params": {"k": "3 N*s/m"}}]})",
                                                         "env.json");
  CHECK(scene.script_count == 2);
  CHECK(scene.effects.size() == 3);
  CHECK(scene.needs.velocity);
  CHECK(std::get<ScriptEffect>(scene.effects[1]).instance_index == 0);
  CHECK(std::get<ScriptEffect>(scene.effects[2]).instance_index == 1);
  ScriptList scripts = make_script_instances(scene);
  EffectInputOf<2> input;
  input.x_m = Vec2{{-0.01, 0.13}};
  input.v_m_per_s = Vec2{{0.1, -0.2}};
  const Vec2 f = sum_effects_N(scene, input, scripts);
  CHECK(f[0] == doctest::Approx(0.25 - 0.3));
  CHECK(f[1] == doctest::Approx(-0.5 + 0.6));

  // A script that reads neither velocity nor time adds no needs.
  const PlanarScene lean = load_planar_environment_text(R"({"device": "haplink", "effects": [
      {"type": "script", "file": "scripts/planar/vortex.lua"}]})",
                                                        "env.json", test::source_path(""));
  CHECK_FALSE(lean.needs.velocity);
}

TEST_CASE("planar scripts: the tick renders a script's force through the linkage, and a run reports its fault") {
  const PlanarScene scene = load_planar_environment_text(R"({"device": "haplink", "effects": [
      {"type": "script", "source": "function force(s) if s.t > 0.5 then return 0/0, 0 end return 0.3, -0.2 end"}]})",
                                                         "env.json");
  TickStateOf<2> state = make_tick_state(scene);
  const PlanarReading reading = planar_reading_for(scene.device_model.model, Vec2{});
  for (int i = 0; i < 400; ++i) step(scene, reading, &state);
  CHECK(state.effects_force_N[0] == 0.3);
  CHECK(state.effects_force_N[1] == -0.2);
  CHECK(state.script_calls == 400);
  for (int i = 0; i < 200; ++i) step(scene, reading, &state);
  CHECK(state.scripts[0]->disabled());
  CHECK(state.effects_force_N[0] == 0.0);
  CHECK(state.effects_force_N[1] == 0.0);
  CHECK(std::string(state.scripts[0]->fault_message()).find("force(s) returned nan, 0") != std::string::npos);
}

TEST_CASE("planar scripts: steady state allocates nothing per call") {
  for (const std::string& name : kScripts) {
    CAPTURE(name);
    auto script = start(name);
    const auto sweep = [&] {
      for (int i = 0; i < 10000; ++i) {
        const double phase = 0.01 * i;
        script->force_N(PlanarScriptInput{Vec2{{-0.015 + 0.04 * std::sin(phase), 0.127 + 0.03 * std::cos(phase)}},
                                          Vec2{{0.1, -0.1}}, 0.001 * i, 0.001});
      }
    };
    sweep();
    const std::uint64_t allocations = script->allocation_count();
    const std::size_t bytes = script->memory_bytes();
    sweep();
    CHECK(script->allocation_count() == allocations);
    CHECK(script->memory_bytes() == bytes);
    CHECK_FALSE(script->disabled());
  }
}

}  // namespace
}  // namespace hapscene::HAPSCENE_TEST_FILE
