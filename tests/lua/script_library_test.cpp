// The shipped scripts/: each loads with its defaults and renders the force its header
// comment describes, checked against the formula computed here in C++.
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "engine/base/units.hpp"
#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;
using test::compile_shipped;
using test::read_script;

constexpr double kPi = std::numbers::pi;

// SI value of a unit string, exactly as the params conversion computes it.
double si(const char* text) {
  const QuantityParse q = parse_quantity(text);
  REQUIRE_MESSAGE(q.ok, q.error);
  return q.value_si;
}

std::unique_ptr<ScriptInstance> start(const char* name,
                                      const nlohmann::json& overrides = nlohmann::json::object()) {
  auto script = ScriptInstance::create(compile_shipped(name, overrides));
  script->reset();
  return script;
}

TEST_CASE("library: every script loads, says what it should feel like, and declares params") {
  for (const char* name : {"spring.lua", "texture.lua", "bumps.lua", "detents.lua", "friction.lua",
                           "wall.lua", "mass_spring.lua", "pong.lua", "magnet.lua", "grating.lua",
                           "vibration.lua"}) {
    CAPTURE(name);
    const std::string text = read_script(name);
    CHECK(text.rfind("-- ", 0) == 0);
    CHECK(text.find("Feels like:") != std::string::npos);
    const ScriptProgram program = compile_shipped(name);
    CHECK_FALSE(program.params.empty());
  }
}

TEST_CASE("library: spring.lua matches -K (x - x0) to the last bit") {
  const ScriptProgram program = compile_shipped("spring.lua");
  CHECK_FALSE(program.needs_velocity);
  CHECK_FALSE(program.needs_time);
  auto spring = ScriptInstance::create(program);
  const double K = 100.0;
  const double x0 = 0.0;
  for (double x = -0.05; x <= 0.05; x += 0.00123) CHECK(spring->force_N(at(x)) == -K * (x - x0));

  auto tuned = start("spring.lua", {{"stiffness", "250 N/m"}, {"center", "5 mm"}});
  const double K2 = si("250 N/m");
  const double x02 = si("5 mm");
  for (double x = -0.05; x <= 0.05; x += 0.00123) CHECK(tuned->force_N(at(x)) == -K2 * (x - x02));
}

TEST_CASE("library: texture.lua damps inside the fields and is free in the gaps") {
  const ScriptProgram program = compile_shipped("texture.lua");
  CHECK(program.needs_velocity);
  CHECK_FALSE(program.needs_time);
  auto texture = ScriptInstance::create(program);
  const double B = 0.5;
  // The lab's example field [0.020, 0.025) m, its neighbours, and negative x.
  for (double x : {0.0201, 0.0249, 0.0001, 0.0101, -0.0051, -0.0099}) {
    CAPTURE(x);
    CHECK(texture->force_N(at(x, 0.1)) == -B * 0.1);
    CHECK(texture->force_N(at(x, -0.03)) == -B * -0.03);
  }
  for (double x : {0.0251, 0.0299, 0.0051, -0.0001, -0.0049}) {
    CAPTURE(x);
    CHECK(texture->force_N(at(x, 0.1)) == 0.0);
  }
  // Width 3 mm, gap 7 mm, from 1 mm: fields [1, 4) mm + k 10 mm.
  auto tuned = start("texture.lua", {{"width", "3 mm"}, {"gap", "7 mm"}, {"origin", "1 mm"},
                                     {"damping", "2 N*s/m"}});
  CHECK(tuned->force_N(at(0.0015, 0.1)) == -2.0 * 0.1);
  CHECK(tuned->force_N(at(0.0045, 0.1)) == 0.0);
  CHECK(tuned->force_N(at(-0.0085, 0.1)) == -2.0 * 0.1);
  CHECK(tuned->force_N(at(-0.0095, 0.1)) == 0.0);
}

// bumps.lua's potential U = W h(x) and its force -dU/dx.
struct Bumps {
  double H = si("3 mm"), sigma = si("6 mm"), W = si("4 N"), xb = si("-20 mm"), xv = si("20 mm");
  double g(double u) const { return std::exp(-u * u / (2 * sigma * sigma)); }
  double energy(double x) const { return W * H * (g(x - xb) - g(x - xv)); }
  double force(double x) const {
    return W * H / (sigma * sigma) * ((x - xb) * g(x - xb) - (x - xv) * g(x - xv));
  }
};

TEST_CASE("library: bumps.lua is minus the slope of its potential (conservative)") {
  auto bumps = start("bumps.lua");
  const Bumps model;
  double peak = 0.0;
  for (double x = -0.05; x <= 0.05; x += 0.0005) {
    CAPTURE(x);
    const double f = bumps->force_N(at(x));
    CHECK(f == doctest::Approx(model.force(x)).epsilon(1e-12));
    const double h = 1e-7;
    CHECK(f == doctest::Approx(-(model.energy(x + h) - model.energy(x - h)) / (2 * h)).epsilon(1e-5));
    peak = std::max(peak, std::abs(f));
  }
  CHECK(peak == doctest::Approx(model.W * model.H / model.sigma * std::exp(-0.5)).epsilon(0.01));
  // Uphill before the bump's top pushes back (negative), past it pushes on.
  CHECK(bumps->force_N(at(-0.026)) < 0.0);
  CHECK(bumps->force_N(at(-0.014)) > 0.0);
  // The valley holds: pushed right of its bottom, pulled back left; and vice versa.
  CHECK(bumps->force_N(at(0.024)) < 0.0);
  CHECK(bumps->force_N(at(0.016)) > 0.0);
  // A round trip over both does no net work (trapezoid rule, there and back).
  double work = 0.0;
  double x = -0.05;
  double f = bumps->force_N(at(x));
  for (int leg = 0; leg < 2; ++leg) {
    const double step = leg == 0 ? 0.0001 : -0.0001;
    for (int i = 0; i < 1000; ++i) {
      const double next = x + step;
      const double f_next = bumps->force_N(at(next, step / 0.001));
      work += 0.5 * (f + f_next) * step;
      x = next;
      f = f_next;
    }
  }
  CHECK(std::abs(work) < 1e-12);
}

TEST_CASE("library: detents.lua clicks into notches and is free between them") {
  auto detents = start("detents.lua");
  const double K = 600.0, r = si("4 mm"), p = si("10 mm");
  const auto expected = [&](double x) {
    const double d = x - p * std::floor(x / p + 0.5);
    if (std::abs(d) >= r) return 0.0;
    const double q = 1 - (d / r) * (d / r);
    return -K * d * q * q;
  };
  for (double x = -0.05; x <= 0.05; x += 0.0003) {
    CAPTURE(x);
    CHECK(detents->force_N(at(x)) == doctest::Approx(expected(x)).epsilon(1e-12));
  }
  // Free between notches, pulled toward the nearest centre near one, strongest at r / sqrt(5).
  CHECK(detents->force_N(at(0.005)) == 0.0);
  CHECK(detents->force_N(at(0.012)) < 0.0);
  CHECK(detents->force_N(at(0.018)) > 0.0);
  const double peak = std::abs(detents->force_N(at(0.02 + r / std::sqrt(5.0))));
  CHECK(peak == doctest::Approx(K * r / std::sqrt(5.0) * 0.64).epsilon(1e-9));
  CHECK(peak < 8.0);
  // A capture wider than half the spacing is refused.
  CHECK_THROWS_AS(compile_shipped("detents.lua", {{"capture", "6 mm"}}), InputError);
}

TEST_CASE("library: friction.lua sticks up to the static force, then slips at the kinetic one") {
  auto friction = start("friction.lua");
  const double Fs = 0.8, Fc = 0.5, b = 0.2, dv = si("20 mm/s");
  CHECK(friction->force_N(at(0.0, 0.0)) == 0.0);
  // Stuck: a stiff damper, reaching Fs at the band edge.
  CHECK(friction->force_N(at(0.0, 0.01)) == doctest::Approx(-Fs / dv * 0.01));
  CHECK(friction->force_N(at(0.0, -0.019)) == doctest::Approx(Fs / dv * 0.019));
  // Sliding: Coulomb plus viscous, against the motion.
  CHECK(friction->force_N(at(0.0, 0.1)) == doctest::Approx(-(Fc + b * 0.1)));
  CHECK(friction->force_N(at(0.0, -0.1)) == doctest::Approx(Fc + b * 0.1));
  // Breakaway: the resisting force drops when the handle starts to slide.
  const double stuck = -friction->force_N(at(0.0, dv * 0.999));
  const double sliding = -friction->force_N(at(0.0, dv * 1.001));
  CHECK(stuck > 0.79);
  CHECK(sliding < 0.51);
  CHECK_THROWS_AS(compile_shipped("friction.lua", {{"kinetic_force", "1 N"}}), InputError);
}

TEST_CASE("library: wall.lua is a stiff damped wall with a decaying transient on impact") {
  auto wall = start("wall.lua");
  const double xw = 0.010, K = 600.0, B = 0.5, A = 15.0, f = 150.0, td = si("15 ms");
  const double v = 0.1;
  // Approach at 0.1 m/s; the first tick inside is k = 50 (x = 10.05 mm).
  for (int k = 0; k < 50; ++k) CHECK(wall->force_N(at(0.00505 + v * k * 0.001, v, k * 0.001)) == 0.0);
  const double t_impact = 50 * 0.001;
  const double amplitude = std::min(A * v, 1.5);
  for (int k = 50; k < 140; ++k) {
    CAPTURE(k);
    const double t = k * 0.001;
    const double x = 0.00505 + v * t;
    const double tau = t - t_impact;
    const double transient =
        tau < 5 * td ? -amplitude * std::exp(-tau / td) * std::sin(2 * kPi * f * tau) : 0.0;
    CHECK(wall->force_N(at(x, v, t)) ==
          doctest::Approx(-K * (x - xw) - B * v + transient).epsilon(1e-9));
  }
  // Leaving: only the spring (no damping pulling the hand in), then nothing outside.
  CHECK(wall->force_N(at(0.012, -0.05, 0.2)) == doctest::Approx(-K * 0.002));
  CHECK(wall->force_N(at(0.009, -0.05, 0.25)) == 0.0);
  // A faster impact gives a larger transient (clamped at 1.5 N).
  CHECK(wall->force_N(at(0.0101, 0.5, 0.3)) == doctest::Approx(-K * 0.0001 - B * 0.5));
  const double second = wall->force_N(at(0.0102, 0.5, 0.3 + 0.0015));
  const double expected = -K * 0.0002 - B * 0.5 -
                          1.5 * std::exp(-0.0015 / td) * std::sin(2 * kPi * f * 0.0015);
  CHECK(second == doctest::Approx(expected).epsilon(1e-9));

  // Starting inside the wall is not an impact: no transient.
  auto inside = start("wall.lua");
  CHECK(inside->force_N(at(0.012, 0.1, 0.0)) == doctest::Approx(-K * 0.002 - B * 0.1));
  CHECK(inside->force_N(at(0.0121, 0.1, 0.001)) == doctest::Approx(-K * 0.0021 - B * 0.1));

  // The other side.
  auto left = start("wall.lua", {{"side", "negative"}, {"position", "-10 mm"}});
  CHECK(left->force_N(at(-0.005, -0.1, 0.0)) == 0.0);
  CHECK(left->force_N(at(-0.011, 0.0, 0.01)) == doctest::Approx(K * 0.001));
  CHECK_THROWS_WITH_AS(compile_shipped("wall.lua", {{"side", "up"}}),
                       doctest::Contains("wall: side must be \"positive\" or \"negative\", got \"up\""),
                       InputError);
}

// The exact response of the damped mass to a step of the hand from 0 to x_hand at t = 0.
double mass_position(double t, double x_hand) {
  const double m = 0.2, k = 100.0, kc = 300.0, b = 0.5;
  const double w0 = std::sqrt((k + kc) / m);
  const double zeta = b / (2 * m * w0);
  const double wd = w0 * std::sqrt(1 - zeta * zeta);
  const double xe = kc * x_hand / (k + kc);
  return xe * (1 - std::exp(-zeta * w0 * t) * (std::cos(wd * t) + zeta * w0 / wd * std::sin(wd * t)));
}

TEST_CASE("library: mass_spring.lua integrates its mass stably and accurately") {
  const double kc = 300.0, k = 100.0;
  // Held still, the hand feels the two springs in series, from the first call on.
  auto held = start("mass_spring.lua");
  for (int i = 0; i < 100; ++i) {
    CHECK(held->force_N(at(0.02)) == doctest::Approx(-kc * k / (kc + k) * 0.02).epsilon(1e-9));
  }
  // A step of the hand: the mass follows the exact damped oscillation, at 1 kHz and at
  // 100 Hz (where the script takes substeps).
  for (const double dt : {0.001, 0.01}) {
    CAPTURE(dt);
    auto step = start("mass_spring.lua");
    step->force_N(at(0.0, 0.0, 0.0, dt));
    double worst = 0.0;
    for (int i = 1; i * dt <= 2.0; ++i) {
      const double f = step->force_N(at(0.01, 0.0, i * dt, dt));
      const double xm = 0.01 + f / kc;  // F = -kc (x - xm)
      worst = std::max(worst, std::abs(xm - mass_position(i * dt, 0.01)));
    }
    // Semi-implicit Euler is first order: 2.3 % of the 7.5 mm swing at 1 kHz, 4.5 % at 100 Hz.
    CHECK(worst < (dt < 0.005 ? 0.03 : 0.06) * 0.0075);
  }
  // Without damping the swing neither grows nor decays over 100 s (symplectic Euler).
  auto undamped = start("mass_spring.lua", {{"damping", "0 N*s/m"}});
  undamped->force_N(at(0.0));
  double first_second = 0.0;
  double last_second = 0.0;
  for (int i = 1; i <= 100'000; ++i) {
    const double xm = 0.01 + undamped->force_N(at(0.01, 0.0, i * 0.001)) / kc;
    const double swing = std::abs(xm - 0.0075);
    if (i <= 1000) first_second = std::max(first_second, swing);
    if (i > 99'000) last_second = std::max(last_second, swing);
  }
  CHECK(last_second == doctest::Approx(first_second).epsilon(0.01));
}

TEST_CASE("library: pong.lua serves a ball that taps the paddle and comes back") {
  auto pong = start("pong.lua");
  const double paddle = -0.03;
  // Contact begins when the ball's left edge reaches the paddle: (0.02 - (-0.026)) / 0.15 s.
  const double first_contact = (0.02 - (paddle + 0.004)) / 0.15;
  std::vector<double> contact_starts;
  std::vector<double> peaks;
  bool touching = false;
  for (int i = 1; i <= 1500; ++i) {
    const double t = i * 0.001;
    const double f = pong->force_N(at(paddle, 0.0, t));
    CHECK(f <= 0.0);  // the ball only ever pushes the hand back
    if (f < 0.0 && !touching) {
      contact_starts.push_back(t);
      peaks.push_back(0.0);
    }
    touching = f < 0.0;
    if (touching) peaks.back() = std::max(peaks.back(), -f);
  }
  REQUIRE(contact_starts.size() == 2);
  CHECK(contact_starts[0] == doctest::Approx(first_contact).epsilon(0.01));
  // The tap: an elastic contact, peak v sqrt(kp m).
  CHECK(peaks[0] == doctest::Approx(0.15 * std::sqrt(800.0 * 0.03)).epsilon(0.05));
  // Back after the far wall (restitution 0.9): 0.062 m out at 0.15 m/s and back at 0.135 m/s.
  const double round_trip = 0.062 / 0.15 + 0.062 / 0.135;
  CHECK(contact_starts[1] - contact_starts[0] == doctest::Approx(round_trip + 0.019).epsilon(0.03));
  CHECK(peaks[1] == doctest::Approx(0.9 * peaks[0]).epsilon(0.05));
  // reset() serves again.
  pong->reset();
  CHECK(pong->force_N(at(paddle, 0.0, 0.0)) == 0.0);
}

TEST_CASE("library: magnet.lua pulls harder as the handle nears, then holds it") {
  auto magnet = start("magnet.lua");
  const double Fmax = 2.0, ds = si("3 mm"), R = si("25 mm");
  const double edge = (ds / R) * (ds / R);
  const auto expected = [&](double d) {
    const double distance = std::abs(d);
    if (distance <= ds) return -Fmax * d / ds;
    if (distance >= R) return 0.0;
    const double pull = Fmax / (1 - edge) * ((ds / distance) * (ds / distance) - edge);
    return d > 0 ? -pull : pull;
  };
  for (double x = -0.05; x <= 0.05; x += 0.0007) {
    CAPTURE(x);
    CHECK(magnet->force_N(at(x)) == doctest::Approx(expected(x)).epsilon(1e-12));
  }
  // Continuous at the snap distance and at the range; toward the magnet from both sides.
  CHECK(magnet->force_N(at(ds - 1e-9)) == doctest::Approx(magnet->force_N(at(ds + 1e-9))).epsilon(1e-5));
  CHECK(std::abs(magnet->force_N(at(R - 1e-9))) < 1e-6);
  CHECK(magnet->force_N(at(0.01)) < 0.0);
  CHECK(magnet->force_N(at(-0.01)) > 0.0);
  CHECK(magnet->force_N(at(0.01)) < magnet->force_N(at(0.02)));
}

TEST_CASE("library: grating.lua is a position-only sine") {
  auto grating = start("grating.lua");
  const double A = 0.3, lambda = si("5 mm");
  for (double x = -0.05; x <= 0.05; x += 0.0003) {
    CAPTURE(x);
    CHECK(grating->force_N(at(x, 0.2)) == doctest::Approx(-A * std::sin(2 * kPi / lambda * x)).epsilon(1e-9).scale(1.0));
    CHECK(grating->force_N(at(x, -0.2)) == grating->force_N(at(x, 0.2)));
  }
}

TEST_CASE("library: vibration.lua buzzes in bursts, whatever the position") {
  auto vibration = start("vibration.lua");
  const double A = 0.5, f = 80.0;
  for (int i = 0; i < 2000; ++i) {
    const double t = i * 0.001;
    CAPTURE(t);
    const bool on = std::fmod(t, 0.5) < 0.2;
    const double expected = on ? A * std::sin(2 * kPi * f * t) : 0.0;
    CHECK(vibration->force_N(at(0.01 * (i % 7), 0.0, t)) == doctest::Approx(expected).scale(1.0));
  }
  auto continuous = start("vibration.lua", {{"pulse_period", "0 s"}});
  CHECK(continuous->force_N(at(0.0, 0.0, 0.3 + 1 / (4 * f))) == doctest::Approx(A));
}

}  // namespace
}  // namespace hapscene
