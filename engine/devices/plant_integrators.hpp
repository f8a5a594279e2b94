#pragma once
// Integrators for the simulated handle, one substep at a time with the motor force held
// (the board's sample-and-hold). Three choices, selected in SimulationConfig:
//   semi_implicit_euler  v += a h, then x += v h (first order, cheap; the original default)
//   rk4                  classical fourth-order Runge-Kutta on the full force model
//   exact                the exact solution of the linear part (mass, viscous damping,
//                        hand and end-stop springs and dampers, a force that is constant
//                        or a ramp over the substep) frozen at the substep's start
// Coulomb friction is treated the same way by all three: a handle at rest stays at rest
// while the other forces are below the friction force; otherwise friction is a constant
// force against the direction of motion (or of breakaway) for the whole substep, and a
// velocity that would change sign stops at zero for that substep.
#include <string_view>

namespace hapscene {

enum class PlantIntegrator { semi_implicit_euler, rk4, exact };

// Names on the command line and in reports, in PlantIntegrator order.
inline constexpr std::string_view kPlantIntegratorNames[] = {"euler", "rk4", "exact"};

// m x'' + c x' + k x = f0 + f1 * tau over one substep tau in [0, h]: all coefficients
// frozen at the substep's start. m > 0, c >= 0, k >= 0.
struct LinearModel {
  double mass_kg{};
  double damping_N_s_per_m{};
  double stiffness_N_per_m{};
  double force_N{};            // f0
  double force_rate_N_per_s{}; // f1 (a hand reference moving at constant speed)
};

// Advances (x, v) exactly by h for the linear model (to rounding). Never divides by zero;
// k = 0 and c = 0 are handled.
void exact_linear_step(const LinearModel& model, double h_s, double* x_m, double* v_m_per_s) noexcept;

}  // namespace hapscene
