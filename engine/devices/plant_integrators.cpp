#include "engine/devices/plant_integrators.hpp"

#include <cmath>

namespace hapscene {
namespace {

// exp(A h) for A = [[0, 1], [-k/m, -c/m]], written as E * ((C - mu S) I + S A) with
// mu = -c / 2m, D = mu^2 - k/m and (C, S) = (cosh(qh), sinh(qh)/q) for D = q^2 > 0,
// (cos(qh), sin(qh)/q) for D = -q^2 < 0; a series near D = 0 keeps it smooth. Returns
// E*C and E*S with E = exp(mu h) folded in (so an overdamped step never overflows).
void propagator(double mu, double d, double h_s, double* ec, double* es) noexcept {
  const double dh2 = d * h_s * h_s;
  if (std::abs(dh2) < 1e-4) {
    // Series in D h^2 (error below 1e-20 relative).
    const double e = std::exp(mu * h_s);
    *ec = e * (1.0 + dh2 / 2.0 + dh2 * dh2 / 24.0 + dh2 * dh2 * dh2 / 720.0);
    *es = e * h_s * (1.0 + dh2 / 6.0 + dh2 * dh2 / 120.0 + dh2 * dh2 * dh2 / 5040.0);
  } else if (d > 0.0) {
    // Overdamped: two real eigenvalues mu +/- q, both <= 0 when k >= 0.
    const double q = std::sqrt(d);
    const double e1 = std::exp((mu + q) * h_s);
    const double e2 = std::exp((mu - q) * h_s);
    *ec = 0.5 * (e1 + e2);
    *es = 0.5 * (e1 - e2) / q;
  } else {
    // Underdamped: a decaying rotation.
    const double q = std::sqrt(-d);
    const double e = std::exp(mu * h_s);
    *ec = e * std::cos(q * h_s);
    *es = e * std::sin(q * h_s) / q;
  }
}

}  // namespace

void exact_linear_step(const LinearModel& model, double h_s, double* x_m, double* v_m_per_s) noexcept {
  const double m = model.mass_kg;
  const double c = model.damping_N_s_per_m;
  const double k = model.stiffness_N_per_m;
  const double f0 = model.force_N;
  const double f1 = model.force_rate_N_per_s;

  // No spring: first order in v. With f1 (only a damping-only hand could give one) taken
  // at its mean over the step.
  if (!(k > 0.0)) {
    const double f_N = f0 + 0.5 * f1 * h_s;
    if (c > 0.0) {
      const double r = c / m;
      const double v_inf = f_N / c;
      const double decay = -std::expm1(-r * h_s);  // 1 - exp(-r h), exact for small r h
      *x_m += v_inf * h_s + (*v_m_per_s - v_inf) * decay / r;
      *v_m_per_s = v_inf + (*v_m_per_s - v_inf) * (1.0 - decay);
    } else {
      *x_m += *v_m_per_s * h_s + 0.5 * f_N / m * h_s * h_s;
      *v_m_per_s += f_N / m * h_s;
    }
    return;
  }

  // Particular solution for the ramp force: x_p = a + b tau (b = f1 / k, a = (f0 - c b) / k),
  // then the homogeneous motion of the deviation from it.
  const double b = f1 / k;
  const double a = (f0 - c * b) / k;
  const double d0 = *x_m - a;
  const double e0 = *v_m_per_s - b;
  const double mu = -c / (2.0 * m);
  double ec = 0.0;
  double es = 0.0;
  propagator(mu, mu * mu - k / m, h_s, &ec, &es);
  const double m11 = ec - mu * es;
  const double m12 = es;
  const double m21 = -k / m * es;
  const double m22 = ec + mu * es;
  *x_m = a + b * h_s + m11 * d0 + m12 * e0;
  *v_m_per_s = b + m21 * d0 + m22 * e0;
}

}  // namespace hapscene
